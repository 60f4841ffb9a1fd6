// Finding the DK2's panel among the monitors (gl/headset_monitor.h): by name, else by its
// native portrait mode on a non-primary output, and never an ordinary 1920x1080 desktop.
#include <gtest/gtest.h>

#include "gl/headset_monitor.h"

namespace photovr::gl {
namespace {

MonitorInfo desktop() {
  return {"DELL U2415", 1920, 1080, 60, true};
}

TEST(HeadsetMonitor, FoundByNameWithItsRotation) {
  const HeadsetMonitor portrait =
      pickHeadsetMonitor({desktop(), {"Rift DK2", 1080, 1920, 75, false}});
  EXPECT_EQ(portrait.index, 1);
  EXPECT_EQ(portrait.rotation, 90);  // left unrotated by the OS: turned in the final pass
  const HeadsetMonitor turned = pickHeadsetMonitor({{"OVR Rift", 1920, 1080, 75, true}});
  EXPECT_EQ(turned.index, 0);
  EXPECT_EQ(turned.rotation, 0);  // the desktop already turned it landscape
}

TEST(HeadsetMonitor, FoundByNativeModeOnASecondOutput) {
  const HeadsetMonitor m = pickHeadsetMonitor({desktop(), {"HDMI-1", 1080, 1920, 75, false}});
  EXPECT_EQ(m.index, 1);
  EXPECT_EQ(m.rotation, 90);
}

TEST(HeadsetMonitor, OrdinaryMonitorsAreNeverTaken) {
  EXPECT_EQ(pickHeadsetMonitor({}).index, -1);
  EXPECT_EQ(pickHeadsetMonitor({desktop()}).index, -1);
  EXPECT_EQ(pickHeadsetMonitor({desktop(), {"LG", 1920, 1080, 75, false}}).index, -1);
  // A portrait primary monitor is someone's desktop, not a headset.
  EXPECT_EQ(pickHeadsetMonitor({{"Portrait", 1080, 1920, 60, true}}).index, -1);
  EXPECT_NE(pickHeadsetMonitor({desktop()}).reason.find("none of 1 monitors"), std::string::npos);
}

}  // namespace
}  // namespace photovr::gl
