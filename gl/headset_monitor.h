// Which monitor is the DK2's panel (issue 6, item 5c). The DK2 is an ordinary display to the
// OS: its EDID says manufacturer "OVR" with the name "Rift DK2", and its native mode is
// 1080x1920 portrait at 75 Hz (dk2.md §5), which no desktop monitor runs. A pure function of
// the monitor list, so it is tested without a display; listMonitors() asks GLFW.
#pragma once

#include <string>
#include <vector>

namespace photovr::gl {

struct MonitorInfo {
  std::string name;  // GLFW's human-readable name (from the EDID's display name)
  int width = 0, height = 0, refreshHz = 0;  // current video mode
  bool primary = false;
};

struct HeadsetMonitor {
  int index = -1;    // into the list; -1: none
  int rotation = 0;  // panel rotation for PanelOutput: 90 when the OS leaves it portrait
  std::string reason;
};

// By name first ("Rift", "DK2" or an "OVR" prefix), else the first non-primary monitor in
// the DK2's native 1080x1920 portrait mode. Rotation 90 for a portrait mode (Linux leaves the
// output unrotated; dk2.md §5), 0 when the desktop has already turned it to 1920x1080.
HeadsetMonitor pickHeadsetMonitor(const std::vector<MonitorInfo>& monitors);

// The connected monitors as GLFW sees them (initialises GLFW; empty without a display).
std::vector<MonitorInfo> listMonitors();

}  // namespace photovr::gl
