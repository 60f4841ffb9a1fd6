#include "harness/bench_child.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <stdexcept>
#include <type_traits>

namespace photovr::harness {
namespace {

static_assert(std::is_trivially_copyable_v<FrameRecord>, "sent through a pipe as bytes");

struct Header {
  double peakRssMiB;
  uint64_t rejectedSamples;
  uint64_t frameCount;
};

bool writeAll(int fd, const void* data, size_t bytes) {
  const char* p = static_cast<const char*>(data);
  while (bytes > 0) {
    const ssize_t n = write(fd, p, bytes);
    if (n <= 0) return false;
    p += n, bytes -= size_t(n);
  }
  return true;
}

bool readAll(int fd, void* data, size_t bytes) {
  char* p = static_cast<char*>(data);
  while (bytes > 0) {
    const ssize_t n = read(fd, p, bytes);
    if (n <= 0) return false;
    p += n, bytes -= size_t(n);
  }
  return true;
}

[[noreturn]] void childMain(int fd, const std::function<ConfigResult()>& work) {
  int status = 0;
  try {
    const ConfigResult r = work();
    const Header h{r.peakRssMiB, r.rejectedSamples, r.frames.size()};
    status = writeAll(fd, &h, sizeof h) &&
                     writeAll(fd, r.frames.data(), r.frames.size() * sizeof(FrameRecord))
                 ? 0
                 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "photovr bench: %s\n", e.what());
    status = 1;
  }
  std::fflush(stdout);
  std::fflush(stderr);
  _exit(status);  // no static destructors: they belong to the parent
}

}  // namespace

ConfigResult runInChild(const BenchConfig& config, const std::function<ConfigResult()>& work) {
  int fds[2];
  if (pipe(fds) != 0) throw std::runtime_error("bench: pipe() failed");
  std::fflush(stdout);
  std::fflush(stderr);
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("bench: fork() failed");
  if (pid == 0) {
    close(fds[0]);
    childMain(fds[1], work);
  }
  close(fds[1]);
  ConfigResult r{config, {}, 0.0, 0};
  Header h{};
  bool ok = readAll(fds[0], &h, sizeof h);
  if (ok) {
    r.frames.resize(h.frameCount);
    ok = readAll(fds[0], r.frames.data(), h.frameCount * sizeof(FrameRecord));
  }
  close(fds[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  if (!ok || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw std::runtime_error("bench: configuration " + config.label() + " failed");
  r.peakRssMiB = h.peakRssMiB, r.rejectedSamples = h.rejectedSamples;
  return r;
}

}  // namespace photovr::harness
