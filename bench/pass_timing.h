// What the GL bench tools share: timing a set of passes fairly on a shared machine, the
// scene camera's head turned, and the view-projections of a pair of eyes.
#pragma once

#include <algorithm>
#include <array>
#include <functional>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "core/camera.h"
#include "core/scene.h"
#include "core/stopwatch.h"
#include "gl/panel_output.h"  // waitForGpu

namespace photovr {

// Wall time and process CPU time of a pass (llvmpipe runs GL on the CPU, so CPU time is
// the work; it stays put when something else shares the cores, wall time does not).
struct PassTime {
  double wall = 0, cpu = 0;
  PassTime operator+(const PassTime& o) const { return {wall + o.wall, cpu + o.cpu}; }
};

// The fastest of 'repeats' rounds per pass (the least disturbed: the machine is shared, and
// its other load only ever adds time), the passes alternating within each round so that a
// busy spell falls on all of them; one warm-up round first (llvmpipe compiles shader
// variants on first use). 'finish' ends each pass inside its time: GL passes wait for the
// GPU, CPU passes (bench_passes) need nothing.
inline std::vector<PassTime> bestOfRounds(int repeats,
                                          const std::vector<std::function<void()>>& passes,
                                          const std::function<void()>& finish = gl::waitForGpu) {
  std::vector<PassTime> best(passes.size(), {1e300, 1e300});
  for (int round = 0; round <= repeats; ++round)
    for (size_t p = 0; p < passes.size(); ++p) {
      const auto t0 = Clock::now();
      const double c0 = processCpuMs();
      passes[p]();
      finish();
      const PassTime t{msSince(t0), processCpuMs() - c0};
      if (round > 0) best[p] = {std::min(best[p].wall, t.wall), std::min(best[p].cpu, t.cpu)};
    }
  return best;
}

// The scene's first camera, turned 'yawDeg' about its up axis and moved 'move' (metres, in
// the turned head's frame): a head's motion between render and display.
inline Pose turnedHead(const Scene& s, float yawDeg, glm::vec3 move = glm::vec3(0.0f)) {
  Pose p = poseOf(s.cameras.at(0));
  p.orientation =
      glm::normalize(p.orientation * glm::angleAxis(glm::radians(yawDeg), glm::vec3(0, 1, 0)));
  p.position += p.orientation * move;
  return p;
}

inline std::array<glm::mat4, 2> viewProjections(const std::array<EyeCamera, 2>& eyes) {
  std::array<glm::mat4, 2> vp;
  for (int e = 0; e < 2; ++e) vp[e] = eyes[e].unjitteredProjection() * eyes[e].view();
  return vp;
}

}  // namespace photovr
