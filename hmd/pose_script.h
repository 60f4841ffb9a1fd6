// Pose scripts for the 'sim' headset: CSV with the header t,x,y,z,yaw,pitch,roll
// (seconds, metres, degrees), one pose per row, t strictly increasing. Blank lines and
// lines starting with '#' are skipped. Between rows positions are interpolated linearly
// and orientations by slerp; before the first / after the last row the end pose holds.
//
// Angles: orientation = yaw about +Y, then pitch about the turned +X, then roll about the
// resulting +Z (camera convention of core/camera.h: looking down -Z, +Y up). Positive yaw
// turns left, positive pitch looks up, positive roll tilts the head to the left.
#pragma once

#include <string>
#include <vector>

#include "core/camera.h"

namespace photovr::hmd {

struct PoseKey {
  double t = 0.0;
  Pose pose;
};

glm::quat yawPitchRoll(float yawDeg, float pitchDeg, float rollDeg);

struct PoseScript {
  std::string source;  // file name, for messages
  std::vector<PoseKey> keys;
  Pose sample(double t) const;
  double duration() const { return keys.empty() ? 0.0 : keys.back().t - keys.front().t; }
};

// Throws InputError "<file>: line N: <problem>" on the first bad line.
PoseScript parsePoseScript(const std::string& text, const std::string& source);
PoseScript loadPoseScript(const std::string& path);

}  // namespace photovr::hmd
