#include "hybrid/denoise_input.h"

namespace photovr {

DenoiseInput makeDenoiseInput(const EyeImage& img) {
  DenoiseInput in;
  in.unfiltered.resize(img.color.size());
  bool guided = false;  // any pixel with a replaced guide (NoisyEye::guide)
  for (size_t i = 0; i < img.color.size(); ++i) {
    in.unfiltered[i] = img.color[i] - (img.diffuse[i] * img.diffuseAlbedo[i] +
                                       img.specular[i] * img.specularAlbedo[i]);
    guided |= !img.guide.empty() && img.guide[i] != glm::vec3(0.0f);
  }
  in.eye.width = img.width;
  in.eye.height = img.height;
  in.eye.diffuse = img.diffuse.data();
  in.eye.specular = img.specular.data();
  in.eye.diffuseAlbedo = img.diffuseAlbedo.data();
  in.eye.specularAlbedo = img.specularAlbedo.data();
  in.eye.unfiltered = in.unfiltered.data();
  in.eye.guide = guided ? img.guide.data() : nullptr;
  return in;
}

}  // namespace photovr
