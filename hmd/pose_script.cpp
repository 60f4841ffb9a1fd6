#include "hmd/pose_script.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "core/files.h"

namespace photovr::hmd {
namespace {

constexpr const char* kHeader = "t,x,y,z,yaw,pitch,roll";

std::string trim(const std::string& s) {
  const size_t b = s.find_first_not_of(" \t\r");
  const size_t e = s.find_last_not_of(" \t\r");
  return b == std::string::npos ? "" : s.substr(b, e - b + 1);
}

std::string withoutSpaces(std::string s) {
  s.erase(std::remove_if(s.begin(), s.end(), [](char c) { return c == ' ' || c == '\t'; }),
          s.end());
  return s;
}

bool parseNumber(const std::string& field, double& v) {
  const std::string f = trim(field);
  const auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), v);
  return ec == std::errc() && end == f.data() + f.size() && std::isfinite(v);
}

PoseKey parseRow(const std::string& line, const std::string& where) {
  std::vector<double> v;
  std::stringstream ss(line);
  for (std::string field; std::getline(ss, field, ',');) {
    double x = 0.0;
    if (!parseNumber(field, x))
      throw InputError(where, "'" + trim(field) + "' is not a number (expected " + kHeader + ")");
    // Poses are float: a finite double such as 1e53 would become an infinite position.
    if (!std::isfinite(float(x)))
      throw InputError(where, "'" + trim(field) + "' is beyond float range (about 3.4e38)");
    v.push_back(x);
  }
  if (v.size() != 7 || line.back() == ',')
    throw InputError(where, "expected 7 comma-separated numbers (" + std::string(kHeader) +
                                "), got " + std::to_string(v.size()));
  PoseKey k;
  k.t = v[0];
  k.pose.position = glm::vec3(v[1], v[2], v[3]);
  k.pose.orientation = yawPitchRoll(float(v[4]), float(v[5]), float(v[6]));
  return k;
}

}  // namespace

glm::quat yawPitchRoll(float yaw, float pitch, float roll) {
  return glm::angleAxis(glm::radians(yaw), glm::vec3(0, 1, 0)) *
         glm::angleAxis(glm::radians(pitch), glm::vec3(1, 0, 0)) *
         glm::angleAxis(glm::radians(roll), glm::vec3(0, 0, 1));
}

PoseScript parsePoseScript(const std::string& text, const std::string& source) {
  PoseScript script{source, {}};
  std::stringstream in(text);
  bool header = false;
  int lineNo = 0;
  for (std::string raw; std::getline(in, raw);) {
    ++lineNo;
    const std::string line = trim(raw);
    if (line.empty() || line[0] == '#') continue;
    const std::string where = source + ": line " + std::to_string(lineNo);
    if (!header) {
      if (withoutSpaces(line) != kHeader)
        throw InputError(where, "expected the header " + std::string(kHeader));
      header = true;
      continue;
    }
    PoseKey k = parseRow(line, where);
    if (!script.keys.empty() && k.t <= script.keys.back().t)
      throw InputError(where, "t must increase from row to row");
    script.keys.push_back(k);
  }
  if (script.keys.empty())
    throw InputError(source, header ? "no pose rows after the header"
                                    : "empty (expected the header " + std::string(kHeader) + ")");
  return script;
}

PoseScript loadPoseScript(const std::string& path) {
  return parsePoseScript(readRegularFile(path, "pose script"), path);
}

Pose PoseScript::sample(double t) const {
  if (keys.empty()) return {};
  if (t <= keys.front().t) return keys.front().pose;
  if (t >= keys.back().t) return keys.back().pose;
  const auto next = std::upper_bound(keys.begin(), keys.end(), t,
                                     [](double v, const PoseKey& k) { return v < k.t; });
  const PoseKey& a = *(next - 1);
  const PoseKey& b = *next;
  const float f = float((t - a.t) / (b.t - a.t));
  Pose p;
  p.position = glm::mix(a.pose.position, b.pose.position, f);
  p.orientation = glm::slerp(a.pose.orientation, b.pose.orientation, f);  // shortest arc
  return p;
}

}  // namespace photovr::hmd
