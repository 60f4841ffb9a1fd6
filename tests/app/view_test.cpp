// photovr view under a virtual X server (xvfb-run): it opens its window, renders through
// the headset compositor, draws the Dear ImGui overlay and saves the composited window.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "core/image_io.h"
#include "tests/app/cli_util.h"

namespace photovr {
namespace {

namespace fs = std::filesystem;

constexpr int kWindowW = 640, kWindowH = 360;

// Mean absolute difference of RGB over a rectangle (x0, y0 top-left, inclusive-exclusive).
double meanDiff(const Image8& a, const Image8& b, int x0, int y0, int x1, int y1) {
  double sum = 0.0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x)
      for (int k = 0; k < 3; ++k)
        sum += std::abs(int(a.data[(size_t(y) * a.width + x) * 4 + k]) -
                        int(b.data[(size_t(y) * b.width + x) * 4 + k]));
  return sum / (3.0 * (x1 - x0) * (y1 - y0));
}

double meanLevel(const Image8& a, int x0, int y0, int x1, int y1) {
  Image8 black(a.width, a.height, 4);
  return meanDiff(a, black, x0, y0, x1, y1);
}

TEST(View, DrawsTheOverlayOverTheCompositedFrameUnderXvfb) {
  // Not a skip: scripts/setup.sh installs xvfb, so a missing xvfb-run is a broken set-up.
  ASSERT_EQ(std::system("command -v xvfb-run > /dev/null 2>&1"), 0)
      << "xvfb-run is not installed (scripts/setup.sh installs it)";
  const std::string dir = testing::tempDir("view");
  const std::string script = dir + "/still.csv";
  std::ofstream(script) << "t,x,y,z,yaw,pitch,roll\n0,0,0,0,0,0,0\n10,0,0,0,0,0,0\n";
  const std::string base = std::string("xvfb-run -a -s '-screen 0 1280x720x24' ") + PHOTOVR_BINARY +
                           " view --scene cornell --hmd sim " + script +
                           " --width 64 --height 72 --overscan 2 --window " +
                           std::to_string(kWindowW) + "x" + std::to_string(kWindowH) +
                           " --frames 3 --screenshot ";
  for (const char* variant : {"overlay", "plain"}) {
    const std::string cmd = base + dir + "/" + variant + ".png" +
                            (std::string(variant) == "plain" ? " --no-overlay" : "") + " 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  }
  ASSERT_TRUE(fs::exists(dir + "/overlay.png"));
  const Image8 overlay = readImageRGBA8(dir + "/overlay.png");
  const Image8 plain = readImageRGBA8(dir + "/plain.png");
  ASSERT_EQ(overlay.width, kWindowW);
  ASSERT_EQ(overlay.height, kWindowH);
  ASSERT_EQ(plain.width, kWindowW);
  // The overlay window sits at (8, 8), ~330 px wide: its top-left part covers the scene.
  const double inOverlay = meanDiff(overlay, plain, 12, 12, 200, 80);
  // The right edge of the window is outside it; there the runs differ only by which
  // renderer frame (noise, denoiser history) the third refresh showed.
  const double outside = meanDiff(overlay, plain, 560, 0, kWindowW, kWindowH);
  std::printf("overlay region mean |diff| %.1f, outside %.1f; plain frame mean level %.1f\n",
              inOverlay, outside, meanLevel(plain, 0, 0, kWindowW, kWindowH));
  // The ImGui panel (dark, 85 % opaque, white text) over the Cornell box's lit walls
  // changes every pixel by tens of levels; frame-to-frame noise after denoising by a few.
  EXPECT_GT(inOverlay, 20.0);
  EXPECT_GT(inOverlay, 3.0 * outside);
  // The composited frame is there: the lens-distorted scene is not black.
  EXPECT_GT(meanLevel(plain, 0, 0, kWindowW, kWindowH), 10.0);
}

}  // namespace
}  // namespace photovr
