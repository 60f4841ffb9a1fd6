#include "core/image_io.h"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "core/error.h"

namespace photovr {
namespace {

std::string tempPath(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("photovr-image-io-" + name)).string();
}

TEST(ImageIo, PngKeepsStraightAlphaBothWays) {
  Image8 img(2, 1, 4);
  img.data = {0, 255, 0, 128, 10, 20, 30, 0};  // colour must survive a partly/fully clear alpha
  const std::string path = tempPath("alpha.png");
  writeImage(path, img);
  const Image8 back = readImageRGBA8(path);
  EXPECT_EQ(back.data, img.data);
}

TEST(ImageIo, ExrRoundTripIsExact) {
  ImageF img(3, 2, 1);
  for (size_t i = 0; i < img.data.size(); ++i) img.data[i] = 0.1f * float(i) + 1e-7f;
  const std::string path = tempPath("depth.exr");
  writeImage(path, img);
  EXPECT_EQ(readImageF(path).data, img.data);
}

TEST(ImageIo, FailedWriteLeavesNothingBehind) {
  const std::string dir = tempPath("nowrite");
  std::filesystem::create_directories(dir);
  std::filesystem::permissions(
      dir, std::filesystem::perms::owner_read | std::filesystem::perms::owner_exec);
  Image8 img(1, 1, 3);
  bool threw = false;
  try {
    writeImage(dir + "/x.png", img);
  } catch (const InputError& e) {
    threw = true;
    EXPECT_NE(std::string(e.what()).find(dir + "/x.png"), std::string::npos);
  }
  std::filesystem::permissions(dir, std::filesystem::perms::owner_all);
  // root ignores directory permissions: then the write succeeds, which is also fine.
  if (threw) {
    EXPECT_TRUE(std::filesystem::is_empty(dir));
  }
}

TEST(ImageIo, TruncatedPngIsAOneLineErrorNamingTheFile) {
  const std::string path = tempPath("truncated.png");
  Image8 img(16, 16, 3);
  writeImage(path, img);
  std::filesystem::resize_file(path, 40);
  try {
    readImageRGBA8(path);
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind(path, 0), 0u) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
}

TEST(ImageIo, SrgbTransferRoundTrips) {
  for (float v : {0.0f, 0.001f, 0.04045f, 0.2f, 0.5f, 1.0f})
    EXPECT_NEAR(srgbToLinear(linearToSrgb(v)), v, 1e-6f);
  EXPECT_EQ(toSrgb8(1.0f), 255);
  EXPECT_EQ(toSrgb8(-1.0f), 0);
}

}  // namespace
}  // namespace photovr
