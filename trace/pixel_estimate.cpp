#include "trace/pixel_estimate.h"

namespace photovr {

void addPath(PixelEstimate& e, const glm::vec3& emission, const PathResult& r) {
  e.diffuse += r.diffuse;
  e.specular += r.specular;
  e.albedo += r.albedo;
  e.emitted += emission;
  e.diffuseAlbedo += glm::max(r.diffuseAlbedo, glm::vec3(kMinDemodulationAlbedo));
  e.specularAlbedo += glm::max(r.specularAlbedo, glm::vec3(kMinDemodulationAlbedo));
  if (e.samples == 0) e.guide = r.guide;
  e.rays += r.rays;
  e.rejected += r.rejected;
  e.ownBounces += r.ownBounces;
  ++e.samples;
}

void storePixel(EyeImage& img, size_t i, const PixelEstimate& e) {
  img.samples[i] = e.samples;
  const uint32_t taken = e.samples + e.misses;
  if (taken == 0) return;
  const float inv = 1.0f / float(taken);
  img.color[i] = (e.diffuse + e.specular + e.emitted) * inv;
  if (e.samples == 0) return;
  const float invHits = 1.0f / float(e.samples);
  const glm::vec3 dAlb = e.diffuseAlbedo * invHits, sAlb = e.specularAlbedo * invHits;
  img.diffuse[i] = e.diffuse * inv / dAlb;
  img.specular[i] = e.specular * inv / sAlb;
  img.diffuseAlbedo[i] = dAlb;
  img.specularAlbedo[i] = sAlb;
  img.albedo[i] = e.albedo * invHits;
  img.guide[i] = e.guide;
}

void allocateEyeImage(EyeImage& img, int w, int h) {
  const size_t n = size_t(w) * h;
  img.width = w;
  img.height = h;
  for (auto* v : {&img.color, &img.albedo, &img.normal, &img.diffuse, &img.specular,
                  &img.diffuseAlbedo, &img.specularAlbedo, &img.guide})
    v->assign(n, glm::vec3(0.0f));
  img.depth.assign(n, 0.0f);
  img.samples.assign(n, 0);
}

}  // namespace photovr
