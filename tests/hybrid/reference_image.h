// A converged pure-path-traced image for tests: 'frames' frames of 'spp' samples each
// through 'camera', averaged: one sampler sequence of frames x spp samples per pixel, each
// at its own place in the pixel (the path tracer ignores camera.jitter).
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
    const EyeImage img = renderPathTraced(ctx, camera, 0, uint32_t(f));
    for (size_t i = 0; i < mean.size(); ++i) mean[i] += img.color[i] / float(frames);
  }
  return mean;
}

}  // namespace photovr::testing
