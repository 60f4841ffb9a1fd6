#include "hybrid/denoise_input.h"

namespace photovr {

DenoiseInput makeDenoiseInput(const EyeImage& img) {
  DenoiseInput in;
  in.unfiltered.resize(img.color.size());
  for (size_t i = 0; i < img.color.size(); ++i)
    in.unfiltered[i] = img.color[i] - (img.diffuse[i] * img.diffuseAlbedo[i] +
                                       img.specular[i] * img.specularAlbedo[i]);
  in.eye.width = img.width;
  in.eye.height = img.height;
  in.eye.diffuse = img.diffuse.data();
  in.eye.specular = img.specular.data();
  in.eye.diffuseAlbedo = img.diffuseAlbedo.data();
  in.eye.specularAlbedo = img.specularAlbedo.data();
  in.eye.unfiltered = in.unfiltered.data();
  return in;
}

}  // namespace photovr
