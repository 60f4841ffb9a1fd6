#include "core/exr_header.h"

#include <cstdint>
#include <filesystem>
#include <fstream>

#include "core/error.h"

namespace photovr {
namespace {

// OpenEXR file layout (openexr.com, "OpenEXR File Layout"): magic 20000630 and a 4-byte
// version field (bit 12: multi-part), then headers of attributes, each a null-terminated
// name and type name (at most 255 bytes with the 'long names' bit 10, 31 without), a
// little-endian int32 size and that many bytes of value. A null byte ends a header; a
// multi-part file's list of headers ends with an empty one.
constexpr uint32_t kMagic = 20000630;
constexpr uint32_t kMultiPartBit = 1u << 12;
constexpr size_t kMaxNameLength = 255;

class HeaderReader {
 public:
  HeaderReader(const std::string& path, std::ifstream& in, uintmax_t fileSize)
      : path_(path), in_(in), fileSize_(fileSize) {}

  uint32_t u32(const char* what) {
    unsigned char b[4];
    if (!in_.read(reinterpret_cast<char*>(b), 4)) fail(std::string("ends inside ") + what);
    return uint32_t(b[0]) | uint32_t(b[1]) << 8 | uint32_t(b[2]) << 16 | uint32_t(b[3]) << 24;
  }

  // A null-terminated name; empty at the end of a header.
  std::string name() {
    std::string s;
    for (char c; in_.get(c) && c != '\0';) {
      s += c;
      if (s.size() > kMaxNameLength) fail("an attribute name longer than 255 bytes");
    }
    if (!in_) fail("ends inside an attribute name");
    return s;
  }

  // One attribute after its name: type, size, value skipped.
  void skipValue(const std::string& attribute) {
    name();  // the type name
    const uint32_t size = u32("an attribute size");
    const uintmax_t left = fileSize_ - uintmax_t(in_.tellg());
    if (size > left)
      fail("attribute '" + attribute + "' claims " + std::to_string(size) + " bytes, " +
           std::to_string(left) + " are left in the file");
    in_.seekg(std::streamoff(size), std::ios::cur);
  }

  [[noreturn]] void fail(const std::string& problem) const {
    throw InputError(path_, "corrupt OpenEXR header: " + problem);
  }

 private:
  const std::string& path_;
  std::ifstream& in_;
  uintmax_t fileSize_;
};

}  // namespace

void checkExrHeader(const std::string& path) {
  std::error_code ec;
  const uintmax_t size = std::filesystem::file_size(path, ec);
  std::ifstream in(path, std::ios::binary);
  if (ec || !in) return;  // the reader reports a file it cannot open
  HeaderReader header(path, in, size);
  unsigned char magic[4];
  if (!in.read(reinterpret_cast<char*>(magic), 4)) return;
  if ((uint32_t(magic[0]) | uint32_t(magic[1]) << 8 | uint32_t(magic[2]) << 16 |
       uint32_t(magic[3]) << 24) != kMagic)
    return;
  const bool multiPart = header.u32("the version field") & kMultiPartBit;
  for (int part = 0;; ++part) {
    int attributes = 0;
    for (std::string name = header.name(); !name.empty(); name = header.name(), ++attributes)
      header.skipValue(name);
    // A single-part file has one header; a multi-part one ends with an empty header.
    if (!multiPart || attributes == 0) return;
  }
}

}  // namespace photovr
