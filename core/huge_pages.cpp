#include "core/huge_pages.h"

#include <fcntl.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <vector>

namespace photovr {
namespace {

constexpr const char* kTunable = "glibc.malloc.hugetlb=1";

bool hasHugePageTunable(const char* tunables) {
  return tunables != nullptr &&
         std::string(tunables).find("glibc.malloc.hugetlb") != std::string::npos;
}

// Plain POSIX reads: this runs before libstdc++'s own initialisers (PHOTOVR_PREINIT).
std::string kernelPolicy() {
  char line[256] = {};
  const int fd = open("/sys/kernel/mm/transparent_hugepage/enabled", O_RDONLY | O_CLOEXEC);
  if (fd < 0) return "";
  const ssize_t n = read(fd, line, sizeof line - 1);
  close(fd);
  return n > 0 ? std::string(line, size_t(n)) : "";
}

// The value of 'name' in an environment block, or null.
const char* environmentValue(char** envp, const char* name) {
  const size_t n = std::strlen(name);
  for (char** e = envp; *e != nullptr; ++e)
    if (std::strncmp(*e, name, n) == 0 && (*e)[n] == '=') return *e + n + 1;
  return nullptr;
}

}  // namespace

std::string tunablesWithHugePages(const char* current, const std::string& policy) {
  // "[always]" gives every large region huge pages already; "[never]" gives none.
  if (policy.find("[madvise]") == std::string::npos || hasHugePageTunable(current)) return "";
  return current == nullptr || *current == '\0' ? kTunable : std::string(current) + ":" + kTunable;
}

void useHugePagesForMalloc(int, char** argv, char** envp) {
  // envp, not getenv: libc has not yet set up 'environ' when the pre-initialisers run.
  if (envp == nullptr || environmentValue(envp, "PHOTOVR_HUGE_PAGES") != nullptr) return;
  const char* current = environmentValue(envp, "GLIBC_TUNABLES");
  const std::string tunables = tunablesWithHugePages(current, kernelPolicy());
  if (tunables.empty()) return;
  std::vector<char*> env;
  for (char** e = envp; *e != nullptr; ++e)
    if (std::strncmp(*e, "GLIBC_TUNABLES=", 15) != 0) env.push_back(*e);
  std::string tunablesEntry = "GLIBC_TUNABLES=" + tunables;
  // The mark keeps the re-executed process from looping even if the loader drops the
  // tunable (as it does for privileged programs).
  std::string mark = "PHOTOVR_HUGE_PAGES=1";
  env.push_back(tunablesEntry.data());
  env.push_back(mark.data());
  env.push_back(nullptr);
  execve("/proc/self/exe", argv, env.data());
  // The exec failed: carry on with ordinary pages.
}

bool mallocUsesHugePages() {
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  if (tunables == nullptr) return false;
  const std::string t = tunables, key = "glibc.malloc.hugetlb=";
  const size_t at = t.find(key);
  return at != std::string::npos && at + key.size() < t.size() && t[at + key.size()] != '0';
}

}  // namespace photovr
