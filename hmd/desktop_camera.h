// The 'desktop' head for a plain window: mouse-look plus WASD, as a pure state machine
// (no GLFW here; the app translates its events into DesktopInput).
#pragma once

#include <glm/glm.hpp>

#include "core/camera.h"

namespace photovr::hmd {

struct DesktopInput {
  glm::vec2 mouseDelta{0.0f};  // pixels since the last step; +x right, +y down (window)
  bool forward = false, back = false, left = false, right = false;  // W S A D
  bool up = false, down = false;                                    // E Q
  bool fast = false;                                                // Shift
  float dt = 0.0f;                                                  // seconds
};

struct DesktopSettings {
  // 0.0025 rad per pixel: a 1000-pixel drag turns ~143 deg, the usual FPS feel.
  float radiansPerPixel = 0.0025f;
  float speed = 1.5f;  // m/s, a brisk walk through a room-sized scene
  float fastMultiplier = 4.0f;
  // Looking straight up/down would make yaw degenerate; stop 1 deg short.
  float maxPitch = glm::radians(89.0f);
};

struct DesktopCamera {
  glm::vec3 position{0.0f};
  float yaw = 0.0f, pitch = 0.0f;  // radians; yaw about +Y (positive turns left)

  static DesktopCamera from(const Pose& pose);  // roll is dropped
  Pose pose() const;
};

// Mouse turns (dragging right turns right, dragging down looks down); keys move in the
// horizontal plane of the current heading, E/Q along world Y.
DesktopCamera step(const DesktopCamera& camera, const DesktopInput& input,
                   const DesktopSettings& settings = {});

}  // namespace photovr::hmd
