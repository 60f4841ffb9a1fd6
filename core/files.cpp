#include "core/files.h"

#include <atomic>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "core/error.h"

namespace photovr {
namespace fs = std::filesystem;

std::string readRegularFile(const std::string& path, const std::string& what, size_t maxBytes) {
  std::error_code ec;
  if (path.empty()) throw InputError("(empty path)", "no " + what + " file named");
  if (!fs::exists(path, ec)) throw InputError(path, "file not found");
  if (!fs::is_regular_file(path, ec))
    throw InputError(path, "not a regular file (a folder, FIFO or device), expected " + what);
  const uintmax_t size = fs::file_size(path, ec);
  if (ec || size > maxBytes)
    throw InputError(path, "larger than " + std::to_string(maxBytes) + " bytes");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "cannot open the " + what + " for reading");
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError(path, "read error");
  return bytes;
}

std::string temporaryPathFor(const std::string& path) {
  const fs::path p(path);
  return (p.parent_path() / (".tmp." + std::to_string(getpid()) + "." + p.filename().string()))
      .string();
}

namespace {

// The temporary files being written, removed if SIGINT, SIGTERM or SIGHUP ends the process
// meanwhile (`timeout` sends SIGTERM): the destination is never half-written, and this
// keeps the folder free of the temporary files too. Handlers go only where the signal's
// disposition is still the default, and re-raise it after the removal. Files are written
// concurrently (writeFiles), so each one takes a slot of its own: claimed and released
// with lock-free atomics, which the handler may read.
constexpr size_t kInFlightSlots = 64;
struct InFlightSlot {
  enum : int { kFree, kClaimed, kLive };
  std::atomic<int> state{kFree};
  char path[4096];
};
static_assert(std::atomic<int>::is_always_lock_free, "read from a signal handler");
InFlightSlot inFlight[kInFlightSlots];

void removeInFlightAndDie(int signal) {
  for (InFlightSlot& slot : inFlight)
    if (slot.state.load() == InFlightSlot::kLive) unlink(slot.path);
  ::signal(signal, SIG_DFL);
  raise(signal);
}

void installRemovalHandlers() {
  static const bool installed = [] {
    for (int s : {SIGINT, SIGTERM, SIGHUP}) {
      struct sigaction current {};
      if (sigaction(s, nullptr, &current) == 0 && current.sa_handler == SIG_DFL) {
        struct sigaction handler {};
        handler.sa_handler = removeInFlightAndDie;
        sigemptyset(&handler.sa_mask);
        sigaction(s, &handler, nullptr);
      }
    }
    return true;
  }();
  (void)installed;
}

}  // namespace

InFlightFile::InFlightFile(const std::string& path) {
  installRemovalHandlers();
  if (path.size() >= sizeof InFlightSlot::path) return;
  for (size_t i = 0; i < kInFlightSlots; ++i) {
    int expected = InFlightSlot::kFree;
    if (!inFlight[i].state.compare_exchange_strong(expected, InFlightSlot::kClaimed)) continue;
    std::memcpy(inFlight[i].path, path.c_str(), path.size() + 1);
    inFlight[i].state.store(InFlightSlot::kLive);
    slot_ = int(i);
    return;
  }
}

InFlightFile::~InFlightFile() {
  if (slot_ >= 0) inFlight[size_t(slot_)].state.store(InFlightSlot::kFree);
}

namespace {

// Writes, flushes and syncs; "" on success, else what failed.
std::string writeAndSync(const std::string& file, const void* data, size_t size) {
  FILE* f = std::fopen(file.c_str(), "wb");
  if (!f) return std::strerror(errno);
  std::string why;
  if (size > 0 && std::fwrite(data, 1, size, f) != size) why = std::strerror(errno);
  if (why.empty() && std::fflush(f) != 0) why = std::strerror(errno);
  if (why.empty() && fsync(fileno(f)) != 0) why = std::strerror(errno);
  if (std::fclose(f) != 0 && why.empty()) why = std::strerror(errno);
  return why;
}

}  // namespace

void createOutputFolder(const std::string& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw InputError(dir, "cannot create the output folder: " + ec.message());
  if (!fs::is_directory(dir, ec)) throw InputError(dir, "exists and is not a folder");
}

void moveIntoPlace(const std::string& temporary, const std::string& path) {
  std::error_code ec;
  fs::rename(temporary, path, ec);
  if (!ec) return;
  const std::string why = ec.message();  // before remove() resets ec
  fs::remove(temporary, ec);
  throw InputError(path, "cannot move the finished file into place: " + why);
}

void writeFileAtomically(const std::string& path, const void* data, size_t size) {
  if (path.empty()) throw InputError("(empty path)", "refusing to write a file with no name");
  std::error_code ec;
  const fs::path parent = fs::path(path).parent_path();
  if (!parent.empty()) fs::create_directories(parent, ec);
  const std::string tmp = temporaryPathFor(path);
  const InFlightFile guard(tmp);
  const std::string why = writeAndSync(tmp, data, size);
  if (!why.empty()) {
    fs::remove(tmp, ec);
    throw InputError(path, "cannot write: " + why);
  }
  moveIntoPlace(tmp, path);
}

}  // namespace photovr
