#include "core/image_io.h"

#include <filesystem>
#include <fstream>
#include <vector>

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

// The error of a failed write, or "" when writeImage did not throw.
template <class Img>
std::string writeError(const std::string& path, const Img& img) {
  try {
    writeImage(path, img);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// Both failures below hold for root too (CI runs as root, which ignores permission bits):
// a folder in place of the file fails the rename after the encoder has written the whole
// temporary file, and a file in place of the parent folder fails the open.
TEST(ImageIo, FailedRenameLeavesNothingBehind) {
  const std::string dir = tempPath("rename-fails");
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir + "/x.exr/keep");
  const std::string why = writeError(dir + "/x.exr", ImageF(4, 4, 3));
  ASSERT_NE(why, "") << "writing over a non-empty folder succeeded";
  EXPECT_NE(why.find(dir + "/x.exr"), std::string::npos) << why;
  // Only the folder that was there: no temporary file left beside it, and it is untouched.
  std::vector<std::string> left;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    left.push_back(e.path().filename().string());
  EXPECT_EQ(left, std::vector<std::string>{"x.exr"});
  EXPECT_TRUE(std::filesystem::is_directory(dir + "/x.exr/keep"));
}

// writeFiles writes concurrently, yet a failure is the same whichever thread got there
// first: every file that can be written is, and the error names the first failing one in
// list order. Several files of each kind, so that some run at the same time.
TEST(ImageIo, WriteFilesWritesTheRestAndNamesTheFirstFailure) {
  const std::string dir = tempPath("write-files");
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::vector<OutputFile> files;
  std::vector<std::string> good, bad;
  for (int i = 0; i < 12; ++i) {
    // Every third below a regular file, which fails the open.
    const bool fails = i % 3 == 1;
    if (fails) std::ofstream(dir + "/blocker" + std::to_string(i)) << "not a folder";
    const std::string path = dir + (fails ? "/blocker" + std::to_string(i) + "/x.exr"
                                          : "/ok" + std::to_string(i) + ".exr");
    (fails ? bad : good).push_back(path);
    files.push_back({path, [](const std::string& p) { writeImage(p, ImageF(64, 64, 3)); }});
  }
  std::string why;
  try {
    writeFiles(files);
  } catch (const InputError& e) {
    why = e.what();
  }
  ASSERT_NE(why, "") << "no failure reported";
  EXPECT_NE(why.find(bad.front()), std::string::npos) << why;
  for (const std::string& p : good) EXPECT_TRUE(std::filesystem::exists(p)) << p;
}

TEST(ImageIo, FailedOpenNamesTheFile) {
  const std::string parent = tempPath("not-a-folder");
  std::filesystem::remove_all(parent);
  std::ofstream(parent) << "a file, not a folder";
  const std::string why = writeError(parent + "/x.png", Image8(1, 1, 3));
  ASSERT_NE(why, "") << "writing below a regular file succeeded";
  EXPECT_NE(why.find(parent + "/x.png"), std::string::npos) << why;
  EXPECT_EQ(std::filesystem::file_size(parent), 20u);  // the file in the way is untouched
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
