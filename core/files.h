// Reading and writing whole files under photovr's error policy.
//
// Reading: only regular files (a directory, FIFO or device would block, read forever or
// fail with a confusing message), with a size cap.
//
// Writing: files that are either complete or absent (nothing the user asked to write is
// left half-written). The bytes go to a temporary file beside the destination,
// are flushed to the disk and checked (a full disk shows up at write, flush or fsync, not
// always at the first), and the file is renamed into place; on any failure the temporary
// file is removed and an InputError names the destination and the reason.
#pragma once

#include <cstddef>
#include <string>

namespace photovr {

// The contents of 'path', which must be a regular file of at most maxBytes; an InputError
// naming it and 'what' it should have been otherwise.
std::string readRegularFile(const std::string& path, const std::string& what,
                            size_t maxBytes = size_t(1) << 32);

// ".tmp.<pid>.<name>" beside 'path', its extension kept last (writers pick formats by it).
std::string temporaryPathFor(const std::string& path);

void writeFileAtomically(const std::string& path, const void* data, size_t size);
inline void writeFileAtomically(const std::string& path, const std::string& bytes) {
  writeFileAtomically(path, bytes.data(), bytes.size());
}

// Creates 'dir' (and its parents) for outputs, before any work that would write there:
// an InputError now, not after minutes of rendering, if it cannot be a folder.
void createOutputFolder(const std::string& dir);

// While one lives, its temporary file is removed if SIGINT, SIGTERM or SIGHUP ends the
// process (up to 64 at once: writeFiles writes concurrently; beyond that, a file is not
// covered).
class InFlightFile {
 public:
  explicit InFlightFile(const std::string& temporaryPath);
  ~InFlightFile();
  InFlightFile(const InFlightFile&) = delete;
  InFlightFile& operator=(const InFlightFile&) = delete;

 private:
  int slot_ = -1;  // its slot in the signal handler's list, or none
};

// Renames a finished temporary file into place; on failure removes it and throws.
void moveIntoPlace(const std::string& temporary, const std::string& path);

}  // namespace photovr
