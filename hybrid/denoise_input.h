// A traced eye image as the GL denoiser's input: the demodulated lobes and their albedos
// as they are, plus the radiance the denoiser must not filter (primary emission, and the
// sky in background pixels), which is the colour minus the remodulated lobes.
#pragma once

#include <vector>

#include "gl/denoiser.h"
#include "trace/path_tracer.h"

namespace photovr {

struct DenoiseInput {
  std::vector<glm::vec3> unfiltered;
  gl::NoisyEye eye;  // points into the EyeImage and 'unfiltered': keep both alive
};

DenoiseInput makeDenoiseInput(const EyeImage& image);

}  // namespace photovr
