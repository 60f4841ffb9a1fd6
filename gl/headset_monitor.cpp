#include "gl/headset_monitor.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>

namespace photovr::gl {
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

bool namedLikeDk2(const std::string& name) {
  const std::string n = lower(name);
  return n.find("rift") != std::string::npos || n.find("dk2") != std::string::npos ||
         n.rfind("ovr", 0) == 0;
}

bool nativePortrait(const MonitorInfo& m) {
  return m.width == 1080 && m.height == 1920;
}

HeadsetMonitor chosen(const std::vector<MonitorInfo>& list, size_t i, const std::string& why) {
  const MonitorInfo& m = list[i];
  return {int(i), nativePortrait(m) ? 90 : 0,
          "monitor " + std::to_string(i) + " '" + m.name + "' " + std::to_string(m.width) + "x" +
              std::to_string(m.height) + " @ " + std::to_string(m.refreshHz) + " Hz: " + why};
}

}  // namespace

HeadsetMonitor pickHeadsetMonitor(const std::vector<MonitorInfo>& monitors) {
  for (size_t i = 0; i < monitors.size(); ++i)
    if (namedLikeDk2(monitors[i].name)) return chosen(monitors, i, "named like the DK2");
  for (size_t i = 0; i < monitors.size(); ++i)
    if (!monitors[i].primary && nativePortrait(monitors[i]))
      return chosen(monitors, i, "in the DK2's native 1080x1920 portrait mode");
  HeadsetMonitor none;
  none.reason = "none of " + std::to_string(monitors.size()) +
                " monitors is named like the DK2 or runs its native 1080x1920 mode";
  return none;
}

std::vector<MonitorInfo> listMonitors() {
  std::vector<MonitorInfo> out;
  if (!std::getenv("DISPLAY") && !std::getenv("WAYLAND_DISPLAY")) return out;
  if (!glfwInit()) return out;
  int count = 0;
  GLFWmonitor** monitors = glfwGetMonitors(&count);
  GLFWmonitor* primary = glfwGetPrimaryMonitor();
  for (int i = 0; i < count; ++i) {
    MonitorInfo m;
    const char* name = glfwGetMonitorName(monitors[i]);
    m.name = name ? name : "";
    if (const GLFWvidmode* mode = glfwGetVideoMode(monitors[i]))
      m.width = mode->width, m.height = mode->height, m.refreshHz = mode->refreshRate;
    m.primary = monitors[i] == primary;
    out.push_back(m);
  }
  return out;
}

}  // namespace photovr::gl
