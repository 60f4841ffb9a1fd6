#include "trace/pixel_estimate.h"

namespace photovr {

namespace {

glm::vec4 lanes(const glm::vec3& v) {
  return glm::vec4(v, 0.0f);
}

// A pixel with no path: colour 'color', its lobes, their albedos and the AOVs 0.
void storePathlessPixel(EyeImage& img, size_t i, const glm::vec3& color) {
  img.samples[i] = 0;
  img.color[i] = color;
  for (auto* plane : {&img.diffuse, &img.specular, &img.diffuseAlbedo, &img.specularAlbedo,
                      &img.albedo, &img.guide})
    (*plane)[i] = glm::vec3(0.0f);
}

}  // namespace

void addPath(PixelEstimate& e, const glm::vec3& emission, const PathResult& r) {
  e.diffuse += lanes(r.diffuse);
  e.specular += lanes(r.specular);
  e.albedo += lanes(r.albedo);
  e.emitted += lanes(emission);
  e.diffuseAlbedo += lanes(glm::max(r.diffuseAlbedo, glm::vec3(kMinDemodulationAlbedo)));
  e.specularAlbedo += lanes(glm::max(r.specularAlbedo, glm::vec3(kMinDemodulationAlbedo)));
  if (e.samples == 0) e.guide = r.guide;
  e.rays += r.rays;
  e.rejected += r.rejected;
  e.ownBounces += r.ownBounces;
  ++e.samples;
}

void addMissedRay(PixelEstimate& e, const glm::vec3& environment) {
  e.emitted += lanes(environment);
  ++e.misses;
}

void storePixel(EyeImage& img, size_t i, const PixelEstimate& e) {
  const uint32_t taken = e.samples + e.misses;
  const float inv = taken > 0 ? 1.0f / float(taken) : 0.0f;
  const glm::vec3 color((e.diffuse + e.specular + e.emitted) * inv);
  if (e.samples == 0) return storePathlessPixel(img, i, color);
  img.samples[i] = e.samples;
  img.color[i] = color;
  const float invHits = 1.0f / float(e.samples);
  const glm::vec3 dAlb(e.diffuseAlbedo * invHits), sAlb(e.specularAlbedo * invHits);
  img.diffuse[i] = glm::vec3(e.diffuse * inv) / dAlb;
  img.specular[i] = glm::vec3(e.specular * inv) / sAlb;
  img.diffuseAlbedo[i] = dAlb;
  img.specularAlbedo[i] = sAlb;
  img.albedo[i] = glm::vec3(e.albedo * invHits);
  img.guide[i] = e.guide;
}

// Written directly, not through an estimate of one missed ray: the same values (0 + 0 +
// color, times 1: a -0 becomes +0 as it did there), without the estimate's initialisers and
// division. (1 % of the samples in a profile of spheres' reusing hybrid eye, whose background
// is two fifths of its pixels; in time, within the bench's noise.)
void storeUntracedPixel(EyeImage& img, size_t i, const glm::vec3& color) {
  storePathlessPixel(img, i, color + glm::vec3(0.0f));
}

void sizeEyeImage(EyeImage& img, int w, int h) {
  const size_t n = size_t(w) * h;
  img.width = w;
  img.height = h;
  for (auto* v : {&img.color, &img.albedo, &img.normal, &img.diffuse, &img.specular,
                  &img.diffuseAlbedo, &img.specularAlbedo, &img.guide})
    v->resize(n);
  img.depth.resize(n);
  img.samples.resize(n);
}

void allocateEyeImage(EyeImage& img, int w, int h) {
  sizeEyeImage(img, w, h);
  for (size_t i = 0; i < img.color.size(); ++i) {
    storeUntracedPixel(img, i, glm::vec3(0.0f));
    img.normal[i] = glm::vec3(0.0f);
    img.depth[i] = 0.0f;
  }
}

}  // namespace photovr
