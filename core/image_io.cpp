#include "core/image_io.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>

#include "core/error.h"
#include "core/exr_header.h"
#include "core/files.h"

namespace photovr {
namespace {

namespace fs = std::filesystem;
using OIIO::ImageInput;
using OIIO::ImageOutput;
using OIIO::ImageSpec;
using OIIO::TypeDesc;

// OpenImageIO's messages may span lines; photovr's errors are one line.
std::string firstLine(const std::string& text) {
  const std::string line = text.substr(0, text.find('\n'));
  return line.empty() ? "unknown error" : line;
}

// Through memory where the format's writer takes an IOProxy (PNG, JPEG, ...): their
// writers do not all report a full disk (measured: PNGs truncated with success), so the
// bytes are written and checked by writeFileAtomically. Other formats (OpenEXR, whose
// writer reports write errors) go to a temporary file renamed into place.
void writePixels(const std::string& path, int w, int h, int c, TypeDesc type, const void* pixels) {
  if (w <= 0 || h <= 0 || c <= 0) throw InputError(path, "refusing to write an empty image");
  auto out = ImageOutput::create(path);
  if (!out) throw InputError(path, "no writer for this file type: " + firstLine(OIIO::geterror()));
  ImageSpec spec(w, h, c, type);
  // Colour is straight (unassociated) alpha everywhere in photovr, as in glTF; without
  // this OpenImageIO would premultiply on the way out.
  spec.attribute("oiio:UnassociatedAlpha", 1);
  const auto fail = [&](const std::string& tmp) {
    const std::string why = firstLine(out->geterror());
    out.reset();
    std::error_code ec;
    if (!tmp.empty()) fs::remove(tmp, ec);
    throw InputError(path, "cannot write: " + why);
  };
  if (out->supports("ioproxy")) {
    std::vector<unsigned char> bytes;
    OIIO::Filesystem::IOVecOutput proxy(bytes);
    if (!(out->set_ioproxy(&proxy) && out->open(path, spec) && out->write_image(type, pixels) &&
          out->close()))
      fail("");
    out.reset();
    writeFileAtomically(path, bytes.data(), bytes.size());
    return;
  }
  std::error_code ec;
  const fs::path parent = fs::path(path).parent_path();
  if (!parent.empty()) fs::create_directories(parent, ec);
  const std::string tmp = temporaryPathFor(path);
  const InFlightFile guard(tmp);
  if (!(out->open(tmp, spec) && out->write_image(type, pixels) && out->close())) fail(tmp);
  out.reset();
  moveIntoPlace(tmp, path);
}

}  // namespace

void writeImage(const std::string& path, const ImageF& image) {
  writePixels(path, image.width, image.height, image.channels, TypeDesc::FLOAT, image.data.data());
}

void writeImage(const std::string& path, const Image8& image) {
  writePixels(path, image.width, image.height, image.channels, TypeDesc::UINT8, image.data.data());
}

void writeFiles(const std::vector<OutputFile>& files) {
  std::vector<std::exception_ptr> failed(files.size());
  tbb::parallel_for(size_t(0), files.size(), [&](size_t i) {
    try {
      files[i].write(files[i].path);
    } catch (...) {
      failed[i] = std::current_exception();
    }
  });
  for (const std::exception_ptr& e : failed)
    if (e) std::rethrow_exception(e);
}

ImageF readImageF(const std::string& path) {
  if (!fs::exists(path)) throw InputError(path, "file not found");
  checkExrHeader(path);
  auto in = ImageInput::open(path);
  if (!in) throw InputError(path, "cannot read image: " + firstLine(OIIO::geterror()));
  const ImageSpec& spec = in->spec();
  // At most 2 GiB of float samples (a 16384x8192 RGB environment takes 1.5): a header may
  // claim any size, and the pixels are allocated before a short file shows it lied.
  constexpr int64_t kMaxSamples = int64_t(1) << 29;
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 || spec.nchannels > 64 ||
      int64_t(spec.width) * spec.height * spec.nchannels > kMaxSamples)
    throw InputError(path, "implausible image size " + std::to_string(spec.width) + "x" +
                               std::to_string(spec.height) + "x" + std::to_string(spec.nchannels) +
                               " (at most 2^29 samples)");
  ImageF img(spec.width, spec.height, spec.nchannels);
  try {
    if (!in->read_image(0, 0, 0, spec.nchannels, TypeDesc::FLOAT, img.data.data()))
      throw InputError(path, "corrupt or truncated image: " + firstLine(in->geterror()));
  } catch (const std::bad_alloc&) {
    // The decoder's own buffers for a header's claims within the cap above (fuzzing found
    // a 9830416x8 zip EXR of 480 bytes).
    throw InputError(path, "out of memory decoding a " + std::to_string(spec.width) + "x" +
                               std::to_string(spec.height) + " image");
  }
  return img;
}

static Image8 toRGBA8(std::unique_ptr<ImageInput> in, const std::string& name) {
  const ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 ||
      int64_t(spec.width) * spec.height > (int64_t(1) << 28))
    throw InputError(name, "implausible image size");
  const int c = spec.nchannels;
  std::vector<uint8_t> raw(size_t(spec.width) * spec.height * c);
  if (!in->read_image(0, 0, 0, c, TypeDesc::UINT8, raw.data()))
    throw InputError(name, "corrupt or truncated image: " + firstLine(in->geterror()));
  Image8 img(spec.width, spec.height, 4);
  for (size_t i = 0; i < size_t(spec.width) * spec.height; ++i) {
    const uint8_t* s = &raw[i * c];
    uint8_t* d = &img.data[i * 4];
    d[0] = s[0];
    d[1] = c >= 3 ? s[1] : s[0];
    d[2] = c >= 3 ? s[2] : s[0];
    d[3] = c == 4 ? s[3] : (c == 2 ? s[1] : 255);
  }
  return img;
}

// Asks readers to keep straight alpha (glTF colours are not premultiplied).
static ImageSpec straightAlphaConfig() {
  ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  return config;
}

Image8 readImageRGBA8(const std::string& path) {
  if (!fs::exists(path)) throw InputError(path, "file not found");
  const ImageSpec config = straightAlphaConfig();
  auto in = ImageInput::open(path, &config);
  if (!in) throw InputError(path, "cannot read image: " + firstLine(OIIO::geterror()));
  return toRGBA8(std::move(in), path);
}

Image8 flipToImage(const std::vector<glm::u8vec4>& pixels, int width, int height) {
  Image8 image(width, height, 3);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const glm::u8vec4 c = pixels[size_t(height - 1 - y) * width + x];
      uint8_t* p = image.at(x, y);
      p[0] = c.r, p[1] = c.g, p[2] = c.b;
    }
  return image;
}

}  // namespace photovr
