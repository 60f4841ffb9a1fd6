#include "core/environment_io.h"

#include <gtest/gtest.h>

#include "tests/core/test_dir.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>

#include "core/error.h"
#include "core/image_io.h"

#include <OpenImageIO/imageio.h>

namespace photovr {
namespace {

namespace fs = std::filesystem;

fs::path testDir() {
  return testing::freshTestDir("photovr_environment_io");
}

// 4x2 RGB radiance spanning six orders of magnitude, as real HDR skies do.
ImageF sky() {
  ImageF image(4, 2, 3);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4; ++x) {
      const float base = std::pow(10.0f, float(x + 4 * y) - 3.0f);
      float* p = image.at(x, y);
      p[0] = base;
      p[1] = 0.5f * base;
      p[2] = 0.25f * base;
    }
  return image;
}

std::string loadError(const std::string& path) {
  try {
    loadEnvironment(path);
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    EXPECT_NE(what.find(fs::path(path).filename().string()), std::string::npos) << what;
    return what;
  }
  ADD_FAILURE() << path << " loaded without an error";
  return "";
}

TEST(EnvironmentIo, ExrLoadsExactly) {
  const ImageF image = sky();
  const std::string path = (testDir() / "sky.exr").string();
  writeImage(path, image);
  std::string warning = "unset";
  const Environment env = loadEnvironment(path, &warning);
  EXPECT_EQ(env.type, Environment::Type::Map);
  EXPECT_EQ(env.width, 4);
  EXPECT_EQ(env.height, 2);
  EXPECT_TRUE(warning.empty()) << warning;
  ASSERT_EQ(env.pixels.size(), 8u);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4; ++x) {
      const float* p = image.at(x, y);
      EXPECT_EQ(env.pixels[size_t(y) * 4 + x], glm::vec3(p[0], p[1], p[2]));  // 32-bit float
    }
}

TEST(EnvironmentIo, HdrLoadsWithinRgbePrecision) {
  const ImageF image = sky();
  const std::string path = (testDir() / "sky.hdr").string();
  writeImage(path, image);
  const Environment env = loadEnvironment(path);
  ASSERT_EQ(env.pixels.size(), 8u);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4; ++x)
      for (int c = 0; c < 3; ++c) {
        // RGBE keeps an 8-bit mantissa per channel under the pixel's largest exponent: error
        // up to 1/256 of the largest channel, so 1% of it covers rounding with margin.
        const float expected = image.at(x, y)[c];
        const float largest = image.at(x, y)[0];
        EXPECT_NEAR(env.pixels[size_t(y) * 4 + x][c], expected, 0.01f * largest) << x << y << c;
      }
}

TEST(EnvironmentIo, GrayIsReplicatedAndAlphaDropped) {
  const fs::path dir = testDir();
  ImageF gray(2, 1, 1);
  gray.data = {0.5f, 3.0f};
  writeImage((dir / "gray.exr").string(), gray);
  const Environment g = loadEnvironment((dir / "gray.exr").string());
  EXPECT_EQ(g.pixels.at(1), glm::vec3(3.0f));
  ImageF rgba(2, 1, 4);
  rgba.data = {1, 2, 3, 0.5f, 4, 5, 6, 0};
  writeImage((dir / "rgba.exr").string(), rgba);
  const Environment c = loadEnvironment((dir / "rgba.exr").string());
  EXPECT_EQ(c.pixels.at(0), glm::vec3(1, 2, 3));
  EXPECT_EQ(c.pixels.at(1), glm::vec3(4, 5, 6));
}

TEST(EnvironmentIo, NonTwoToOneAspectIsAWarning) {
  ImageF square(2, 2, 3);
  const std::string path = (testDir() / "square.exr").string();
  writeImage(path, square);
  std::string warning;
  const Environment env = loadEnvironment(path, &warning);
  EXPECT_EQ(env.width, 2);
  EXPECT_NE(warning.find("not 2:1"), std::string::npos) << warning;
}

TEST(EnvironmentIo, NegativeOrNonFinitePixelIsAnError) {
  const fs::path dir = testDir();
  ImageF bad = sky();
  // -1000 beside a blue of 2500 in the same 8x8 block: 40 %, far beyond a codec's error.
  bad.at(1, 0)[2] = -1000.0f;
  writeImage((dir / "negative.exr").string(), bad);
  EXPECT_NE(loadError((dir / "negative.exr").string()).find("pixel (1, 0)"), std::string::npos);
  bad = sky();
  bad.at(3, 1)[0] = std::numeric_limits<float>::infinity();
  writeImage((dir / "inf.exr").string(), bad);
  EXPECT_NE(loadError((dir / "inf.exr").string()).find("pixel (3, 1)"), std::string::npos);
}

// A map clamped to 0 on the ground, dim noise there, a bright sky and a sun: what lossy EXR
// codecs leave negative in it (issue 23: a DWAB panorama was refused over -0.000011).
ImageF clampedPanorama() {
  const int w = 256, h = 128;
  ImageF image(w, h, 3);
  std::mt19937 rng(23);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float v = 0.5f + 0.4f * std::sin(0.05f * float(x)) * float(y) / float(h);
      if (y >= h / 2) v = rng() % 3 == 0 ? 0.0f : float(rng() % 1000) * 1e-6f;
      const float sun = std::hypot(float(x) - 150.0f, float(y) - 30.0f) < 3.0f ? 2e4f : 0.0f;
      float* p = image.at(x, y);
      p[0] = v + sun, p[1] = 0.8f * v + sun, p[2] = 1.2f * v + 0.9f * sun;
    }
  return image;
}

TEST(EnvironmentIo, LossyCodecNegativesAreClampedWithOneWarning) {
  const ImageF image = clampedPanorama();
  for (const char* codec : {"dwaa", "dwab", "b44"}) {
    const std::string path = (testDir() / (std::string(codec) + ".exr")).string();
    {
      auto out = OIIO::ImageOutput::create(path);
      OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeDesc::HALF);
      spec.attribute("compression", codec);
      ASSERT_TRUE(out && out->open(path, spec));
      ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, image.data.data()));
      out->close();
    }
    const ImageF decoded = readImageF(path);
    size_t negatives = 0;
    float mostNegative = 0.0f;
    for (float v : decoded.data)
      if (v < 0.0f) ++negatives, mostNegative = std::min(mostNegative, v);
    ASSERT_GT(negatives, 0u) << codec << ": the codec left no negative to test";
    std::string warning;
    const Environment env = loadEnvironment(path, &warning);
    EXPECT_NE(warning.find("clamped " + std::to_string(negatives) + " small negative values"),
              std::string::npos)
        << codec << ": " << warning;
    char most[32];
    std::snprintf(most, sizeof most, "most negative %.3g", double(mostNegative));
    EXPECT_NE(warning.find(most), std::string::npos) << codec << ": " << warning;
    EXPECT_EQ(warning.find('\n'), std::string::npos) << warning;
    // Everything else as decoded: the clamp only lifts the negatives to 0.
    for (int y = 0; y < env.height; ++y)
      for (int x = 0; x < env.width; ++x)
        for (int c = 0; c < 3; ++c)
          EXPECT_EQ(env.pixels[size_t(y) * env.width + x][c], std::max(decoded.at(x, y)[c], 0.0f));
  }
}

TEST(EnvironmentIo, MissingFileIsAnError) {
  EXPECT_NE(loadError((testDir() / "absent.hdr").string()).find("not found"), std::string::npos);
}

TEST(EnvironmentIo, TruncatedHdrIsAnError) {
  const fs::path dir = testDir();
  ImageF big(64, 32, 3);
  for (size_t i = 0; i < big.data.size(); ++i) big.data[i] = float(i % 97) * 0.37f;
  writeImage((dir / "full.hdr").string(), big);
  std::ifstream in(dir / "full.hdr", std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::ofstream(dir / "cut.hdr", std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  loadError((dir / "cut.hdr").string());
}

std::string fileBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// OpenEXR allocates what a header attribute claims: one byte of a string's length flipped
// made it allocate 956 MB and take 4 s to fail. The claim is checked against the file's size
// first (core/exr_header.h), and a header cut short is named as such.
TEST(EnvironmentIo, ExrAttributeClaimingMoreThanTheFileIsAnError) {
  const fs::path dir = testDir();
  writeImage((dir / "sky.exr").string(), sky());
  std::string bytes = fileBytes(dir / "sky.exr");
  // The first attribute: after the magic and version (8 bytes), its name and type name
  // (null-terminated), then its little-endian int32 size.
  const size_t nameEnd = bytes.find('\0', 8), typeEnd = bytes.find('\0', nameEnd + 1);
  const std::string name = bytes.substr(8, nameEnd - 8);
  bytes[typeEnd + 4] = char(0x39);  // the size's high byte: ~956 MB
  std::ofstream(dir / "claims.exr", std::ios::binary) << bytes;
  const std::string error = loadError((dir / "claims.exr").string());
  EXPECT_NE(error.find("corrupt OpenEXR header: attribute '" + name + "' claims"),
            std::string::npos)
      << error;
  std::ofstream(dir / "cut.exr", std::ios::binary) << bytes.substr(0, typeEnd + 3);
  EXPECT_NE(loadError((dir / "cut.exr").string()).find("corrupt OpenEXR header: ends inside"),
            std::string::npos);
}

// Bounded fuzzing (fixed seed): mutated .hdr files and .exr headers load or fail with one
// InputError line, never another exception or a crash (the ASan build runs this too). The
// EXR mutants are limited to the header, which checkExrHeader reads: mutants of the pixel
// data can make OpenEXR decode a claimed 9830416x8 image for seconds before it fails
// ("out of memory decoding"), too slow for a test. By hand, 20 000 .hdr mutants ran clean,
// and 3000 whole-file .exr mutants did after the two fixes these tests cover.
TEST(EnvironmentIo, MutatedFilesLoadOrFailWithOneLine) {
  const fs::path dir = testDir();
  ImageF image(16, 8, 3);
  for (size_t i = 0; i < image.data.size(); ++i) image.data[i] = 0.1f + float(i % 7);
  writeImage((dir / "seed.hdr").string(), image);
  writeImage((dir / "seed.exr").string(), image);
  std::mt19937 rng(20261202);
  int loaded = 0, refused = 0;
  for (const char* ext : {"hdr", "exr"}) {
    const std::string seed = fileBytes(dir / (std::string("seed.") + ext));
    const size_t span = ext == std::string("exr") ? seed.find("dataWindow") : seed.size();
    const std::string path = (dir / (std::string("mutant.") + ext)).string();
    for (int it = 0; it < 400; ++it) {
      std::string s = seed;
      switch (rng() % 3) {
        case 0:
          for (int k = 0, n = 1 + int(rng() % 4); k < n; ++k) s[rng() % span] = char(rng());
          break;
        case 1:
          s.erase(rng() % span, 1 + rng() % 16);
          break;
        default:
          s.resize(rng() % span);
      }
      std::ofstream(path, std::ios::binary | std::ios::trunc) << s;
      try {
        loadEnvironment(path);
        ++loaded;
      } catch (const InputError& e) {
        ASSERT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
        ++refused;
      } catch (const std::exception& e) {
        FAIL() << ext << " mutant " << it << ": " << e.what();
      }
    }
  }
  std::printf("environment fuzz: %d loaded, %d refused with one line\n", loaded, refused);
  EXPECT_GT(refused, 0);
}

}  // namespace
}  // namespace photovr
