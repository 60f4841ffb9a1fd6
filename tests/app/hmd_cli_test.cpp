// photovr render --hmd: headless sequences through the headset compositor, driven by a pose
// script or a recorded (here: synthesised, byte-exact) DK2 HID stream, and its errors.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include <gtest/gtest.h>

#include "core/camera.h"
#include "core/image_io.h"
#include "hmd/recording.h"
#include "hmd/synthetic.h"
#include "tests/app/cli_util.h"
#include "tests/core/skinned_glb.h"

namespace photovr {
namespace {

using testing::runPhotovr;
using testing::tempDir;
namespace fs = std::filesystem;

constexpr const char* kTiny = " --scene cornell --width 16 --height 18 --panel 64x36";

std::vector<std::vector<double>> readCsv(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);  // header
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::stringstream ss(line);
    for (std::string field; std::getline(ss, field, ',');) row.push_back(std::stod(field));
    rows.push_back(row);
  }
  return rows;
}

// The mean x (pixels) of an eye image's lit pixels.
double litCentroidX(const std::string& png) {
  Image8 img = readImageRGBA8(png);
  double sum = 0.0, n = 0.0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      if (img.at(x, y)[0] > 64) sum += x, n += 1.0;
  return n > 0.0 ? sum / n : -1.0;
}

// Issue 23: the scene clock runs with the sequence's. The glowing skinned bar folds its tip
// back over 1 s (tests/core/skinned_glb.h): at 2 frames a second, frame 2 (t = 1 s) shows it
// half as long as frame 0, its lit pixels' centroid well left of frame 0's (the head stays
// still; jitter moves it by under a pixel).
TEST(HmdCli, SimSequencePlaysTheSceneOnItsClock) {
  const std::string dir = tempDir("hmd-animated");
  testing::SkinOptions bar;
  bar.emissive = true;
  const std::string scene = testing::skinnedFile(dir, bar);
  std::ofstream(dir + "/still.csv") << "t,x,y,z,yaw,pitch,roll\n0,0,0,0,0,0,0\n";
  const auto r = runPhotovr("render --hmd sim " + dir + "/still.csv --frames 3 --fps 2 --scene " +
                            scene + " --width 48 --height 54 --panel 64x36 --out " + dir + "/out");
  ASSERT_EQ(r.status, 0) << r.output;
  const double at0 = litCentroidX(dir + "/out/0000_left.png");
  const double at1 = litCentroidX(dir + "/out/0002_left.png");
  ASSERT_GT(at0, 0.0) << "nothing lit";
  EXPECT_LT(at1, at0 - 2.0) << at0 << " -> " << at1;
}

TEST(HmdCli, SimSequenceWritesEyesPanelAndTimes) {
  const std::string dir = tempDir("hmd-sim");
  std::ofstream(dir + "/poses.csv") << "t,x,y,z,yaw,pitch,roll\n0,0,0,0,0,0,0\n1,0.3,0,0,30,0,0\n";
  const auto r = runPhotovr("render --hmd sim " + dir + "/poses.csv --frames 2 --rotate 90" +
                            kTiny + " --out " + dir + "/out");
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* f : {"0000_left.png", "0000_right.png", "0000_panel.png", "0001_panel.png"})
    EXPECT_TRUE(fs::exists(dir + "/out/" + f)) << f;
  const Image8 panel = readImageRGBA8(dir + "/out/0001_panel.png");
  EXPECT_EQ(panel.width, 36);  // 64x36 turned by 90 degrees
  EXPECT_EQ(panel.height, 64);
  const auto rows = readCsv(dir + "/out/hmd_frames.csv");
  ASSERT_EQ(rows.size(), 2u);
  // Timing model: frame k rendered at k / 30 s, shown one renderer frame later.
  EXPECT_NEAR(rows[1][1], 1.0 / 30.0, 1e-6);
  EXPECT_NEAR(rows[1][2], 2.0 / 30.0, 1e-6);
  // 30 deg/s and 0.3 m/s over 1/30 s (the script interpolates linearly and by slerp).
  EXPECT_NEAR(rows[1][3], 1.0, 1e-3);
  EXPECT_NEAR(rows[1][4], 0.01, 1e-5);
}

TEST(HmdCli, OverscanRendersWiderEyesAndCoversTheTurn) {
  const std::string dir = tempDir("hmd-overscan");
  // 60 deg/s: the frame shown at 1/30 s is re-projected over a 2 deg turn.
  std::ofstream(dir + "/poses.csv") << "t,x,y,z,yaw,pitch,roll\n0,0,0,0,0,0,0\n1,0,0,0,60,0,0\n";
  const std::string common = "render --hmd sim " + dir + "/poses.csv --frames 1 --scene cornell " +
                             "--width 48 --height 54 --panel 192x108 --denoise off --out ";
  auto r = runPhotovr(common + dir + "/plain");
  ASSERT_EQ(r.status, 0) << r.output;
  r = runPhotovr(common + dir + "/over --overscan 3");
  ASSERT_EQ(r.status, 0) << r.output;
  // The eyes grow by 3 deg a side at the field's pixels per tan-angle (core/camera.h).
  const Image8 left = readImageRGBA8(dir + "/over/0000_left.png");
  EXPECT_EQ(left.width, StereoLayout::dk2(48, 54, glm::radians(3.0f)).width);
  EXPECT_GT(left.width, 48);
  EXPECT_GT(left.height, 54);
  // The panel is the same size. The plain frame leaves the strip the turn brings in
  // uncovered (measured: 6.3 % of the lens-visible pixels disoccluded); the overscanned one
  // only the parallax disocclusions, filled (1.6 %): the head turns about its centre, so
  // the eyes move 1 mm, and at 48x54 pixels every silhouette pixel counts.
  const auto plain = readCsv(dir + "/plain/hmd_frames.csv");
  const auto over = readCsv(dir + "/over/hmd_frames.csv");
  ASSERT_EQ(plain.size(), 1u);
  ASSERT_EQ(over.size(), 1u);
  EXPECT_NEAR(over[0][3], 2.0, 1e-3);  // rotation_delta_deg
  EXPECT_LT(over[0][5] + over[0][6], (plain[0][5] + plain[0][6]) / 3);
  // uncovered_left and _right: nothing with overscan, the strip without.
  ASSERT_EQ(over[0].size(), 11u);
  EXPECT_GT(plain[0][9] + plain[0][10], 0.0);
  EXPECT_EQ(over[0][9] + over[0][10], 0.0);
  EXPECT_EQ(readImageRGBA8(dir + "/over/0000_panel.png").width, 192);
}

TEST(HmdCli, ReplayedRecordingDrivesTheHead) {
  const std::string dir = tempDir("hmd-replay");
  hmd::MotionScript motion;
  motion.segments = {{0.5, {0.0, 1.0, 0.0}}};  // 1 rad/s about +Y
  const hmd::SyntheticStream stream = hmd::synthesize(motion);
  {
    hmd::RecordingWriter w(dir + "/turn.pvrhid");
    for (size_t i = 0; i < stream.reports.size(); ++i)
      w.write({hmd::HidRecord::Input, uint64_t(stream.reportTimes[i] * 1e9),
               std::vector<uint8_t>(stream.reports[i].begin(), stream.reports[i].end())});
  }
  const auto r = runPhotovr("render --hmd replay " + dir + "/turn.pvrhid --frames 3" + kTiny +
                            " --out " + dir + "/out");
  ASSERT_EQ(r.status, 0) << r.output;
  const auto rows = readCsv(dir + "/out/hmd_frames.csv");
  ASSERT_EQ(rows.size(), 3u);
  for (const auto& row : rows)
    // 1 rad/s over one renderer frame (1/30 s) = 1.91 deg. Poses are held per 1 ms sample
    // (up to 0.057 deg off at each end) and fusion integrates the gyro exactly.
    EXPECT_NEAR(row[3], 1000.0 / 30.0 * 180.0 / M_PI / 1000.0, 0.12);
}

TEST(HmdCli, BadHeadsetInputIsAOneLineError) {
  const std::string dir = tempDir("hmd-errors");
  std::ofstream(dir + "/bad.csv") << "t,x,y,z,yaw,pitch,roll\n0,0,0,0,0,0,0\n1,0,zero,0,0,0,0\n";
  struct Case {
    std::string args, message;
    int status;
  } cases[] = {
      {"--hmd sim " + dir + "/missing.csv", dir + "/missing.csv: file not found", 1},
      {"--hmd sim " + dir + "/bad.csv", dir + "/bad.csv: line 3: 'zero' is not a number", 1},
      {"--hmd dk2", "--hmd dk2: no Rift DK2", 1},
      {"--hmd replay " + dir + "/bad.csv", dir + "/bad.csv: not a photovr HID recording", 1},
      {"--hmd sim", "--hmd sim: missing FILE", 2},
      {"--hmd sim " + dir + "/bad.csv --frames 0", "--frames: 0 is out of range", 2},
      {"--hmd vive", "--hmd: 'vive' is not one of", 2},
      {"--fps 10", "--fps: needs --hmd", 2},
      {"--overscan 2", "--overscan: needs --hmd", 2},
      {"--hmd sim " + dir + "/bad.csv --overscan 11", "--overscan: 11 is out of range", 2},
  };
  for (const Case& c : cases) {
    const auto r = runPhotovr("render" + std::string(kTiny) + " --out " + dir + "/out " + c.args);
    EXPECT_EQ(r.status, c.status) << c.args << ": " << r.output;
    EXPECT_NE(r.output.find(c.message), std::string::npos) << c.args << ": " << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  }
}

TEST(HmdCli, ViewRejectsBadInputBeforeOpeningAWindow) {
  const std::string dir = tempDir("view-errors");
  struct Case {
    std::string args, message;
    int status;
  } cases[] = {
      {"--hmd sim " + dir + "/missing.csv", dir + "/missing.csv: file not found", 1},
      {"--frames 0", "--frames: 0 is out of range", 2},
      {"--screenshot " + dir + "/x.png", "--screenshot: needs --frames", 2},
      {"--window 10", "--window: '10' is not WIDTHxHEIGHT", 2},
      {"--overscan -1", "--overscan: -1 is out of range", 2},
  };
  for (const Case& c : cases) {
    const auto r = runPhotovr("view --scene cornell " + c.args);
    EXPECT_EQ(r.status, c.status) << c.args << ": " << r.output;
    EXPECT_NE(r.output.find(c.message), std::string::npos) << c.args << ": " << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  }
}

}  // namespace
}  // namespace photovr
