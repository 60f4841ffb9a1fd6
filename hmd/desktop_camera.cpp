#include "hmd/desktop_camera.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/quaternion.hpp>

namespace photovr::hmd {

DesktopCamera DesktopCamera::from(const Pose& pose) {
  const glm::vec3 f = pose.orientation * glm::vec3(0, 0, -1);
  DesktopCamera c;
  c.position = pose.position;
  c.yaw = std::atan2(-f.x, -f.z);
  c.pitch = std::asin(std::clamp(f.y, -1.0f, 1.0f));
  return c;
}

Pose DesktopCamera::pose() const {
  Pose p;
  p.position = position;
  p.orientation =
      glm::angleAxis(yaw, glm::vec3(0, 1, 0)) * glm::angleAxis(pitch, glm::vec3(1, 0, 0));
  return p;
}

DesktopCamera step(const DesktopCamera& c, const DesktopInput& in, const DesktopSettings& s) {
  DesktopCamera n = c;
  n.yaw = std::remainder(c.yaw - in.mouseDelta.x * s.radiansPerPixel, 2.0f * glm::pi<float>());
  n.pitch = std::clamp(c.pitch - in.mouseDelta.y * s.radiansPerPixel, -s.maxPitch, s.maxPitch);
  const glm::vec3 forward(-std::sin(n.yaw), 0.0f, -std::cos(n.yaw));
  const glm::vec3 right(std::cos(n.yaw), 0.0f, -std::sin(n.yaw));
  glm::vec3 move = forward * float(in.forward - in.back) + right * float(in.right - in.left) +
                   glm::vec3(0, 1, 0) * float(in.up - in.down);
  if (glm::dot(move, move) > 0.0f) move = glm::normalize(move);  // diagonals not faster
  n.position += move * s.speed * (in.fast ? s.fastMultiplier : 1.0f) * in.dt;
  return n;
}

}  // namespace photovr::hmd
