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

// Fills 'input' from 'image', in parallel, into the storage 'input' already has (a frame's
// worth at 960x1080 is 12 MB an eye, whose first touch the frame would pay again: the
// pipeline keeps one per eye). Serial and into fresh storage, this was ~9 ms a frame at
// 960x1080 on 2 cores here, a CPU pass inside the denoise stage that more cores did not
// shorten (docs/MEASUREMENTS.md, "Memory reuse").
void fillDenoiseInput(const EyeImage& image, DenoiseInput& input);

// The same into new storage (benches, tests).
DenoiseInput makeDenoiseInput(const EyeImage& image);

}  // namespace photovr
