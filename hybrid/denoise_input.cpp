#include "hybrid/denoise_input.h"

#include <atomic>

#include "core/parallel_ranges.h"

namespace photovr {

void fillDenoiseInput(const EyeImage& img, DenoiseInput& in) {
  const size_t n = img.color.size();
  in.unfiltered.resize(n);
  const bool hasGuide = !img.guide.empty();
  std::atomic<bool> guided{false};  // any pixel with a replaced guide (NoisyEye::guide)
  parallelRanges(n, [&](size_t begin, size_t end) {
    bool any = false;
    for (size_t i = begin; i < end; ++i) {
      in.unfiltered[i] = img.color[i] - (img.diffuse[i] * img.diffuseAlbedo[i] +
                                         img.specular[i] * img.specularAlbedo[i]);
      any |= hasGuide && img.guide[i] != glm::vec3(0.0f);
    }
    if (any) guided.store(true, std::memory_order_relaxed);
  });
  in.eye.width = img.width;
  in.eye.height = img.height;
  in.eye.diffuse = img.diffuse.data();
  in.eye.specular = img.specular.data();
  in.eye.diffuseAlbedo = img.diffuseAlbedo.data();
  in.eye.specularAlbedo = img.specularAlbedo.data();
  in.eye.unfiltered = in.unfiltered.data();
  in.eye.guide = guided ? img.guide.data() : nullptr;
}

DenoiseInput makeDenoiseInput(const EyeImage& img) {
  DenoiseInput in;
  fillDenoiseInput(img, in);
  return in;
}

}  // namespace photovr
