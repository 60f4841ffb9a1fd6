// A converged pure-path-traced image for tests: 'frames' Halton-jittered frames of 'spp'
// samples each through 'camera' (its own jitter is replaced), averaged.
#pragma once

#include <vector>

#include "trace/path_tracer.h"

namespace photovr::testing {

inline std::vector<glm::vec3> referenceImage(const Scene& scene, EyeCamera camera, int frames,
                                             int spp, uint32_t seed) {
  const EmbreeScene embree(scene);
  const LightSet lights(scene);
  TraceSettings t;
  t.samplesPerPixel = spp;
  t.seed = seed;  // independent of the images it judges
  const TraceContext ctx{scene, embree, lights, t};
  std::vector<glm::vec3> mean(size_t(camera.width) * camera.height, glm::vec3(0.0f));
  for (int f = 0; f < frames; ++f) {
    camera.jitter = haltonJitter(uint32_t(f));
    const EyeImage img = renderPathTraced(ctx, camera, 0, uint32_t(f));
    for (size_t i = 0; i < mean.size(); ++i) mean[i] += img.color[i] / float(frames);
  }
  return mean;
}

}  // namespace photovr::testing
