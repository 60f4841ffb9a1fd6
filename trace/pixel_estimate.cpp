#include "trace/pixel_estimate.h"

#include "trace/bsdf.h"

namespace photovr {

PixelEstimate estimatePixel(const TraceContext& ctx, const SurfaceHit& hit, const glm::vec3& dir,
                            SampleCounters counters, uint32_t spp) {
  PixelEstimate e;
  for (uint32_t s = 0; s < spp; ++s) {
    counters.sample = s;
    const PathResult r = continuePath(ctx, hit, -dir, counters);
    e.diffuse += r.diffuse;
    e.specular += r.specular;
    e.albedo += r.albedo;
    e.rays += r.rays;
    e.rejected += r.rejected;
  }
  e.samples = spp;
  return e;
}

void storePixel(EyeImage& img, size_t i, const SurfaceHit& hit, const glm::vec3& dir,
                const PixelEstimate& e) {
  img.samples[i] = e.samples;
  if (e.samples == 0) return;
  const float inv = 1.0f / float(e.samples);
  const glm::vec3 dAlb = glm::max(diffuseAlbedo(hit.bsdf), glm::vec3(kMinDemodulationAlbedo));
  const glm::vec3 sAlb = glm::max(specularAlbedo(hit.bsdf, glm::dot(hit.shadingNormal, -dir)),
                                  glm::vec3(kMinDemodulationAlbedo));
  img.color[i] = (e.diffuse + e.specular) * inv + hit.emission;
  img.diffuse[i] = e.diffuse * inv / dAlb;
  img.specular[i] = e.specular * inv / sAlb;
  img.diffuseAlbedo[i] = dAlb;
  img.specularAlbedo[i] = sAlb;
  img.albedo[i] = e.albedo * inv;
}

void allocateEyeImage(EyeImage& img, int w, int h) {
  const size_t n = size_t(w) * h;
  img.width = w;
  img.height = h;
  for (auto* v : {&img.color, &img.albedo, &img.normal, &img.diffuse, &img.specular,
                  &img.diffuseAlbedo, &img.specularAlbedo})
    v->assign(n, glm::vec3(0.0f));
  img.depth.assign(n, 0.0f);
  img.samples.assign(n, 0);
}

}  // namespace photovr
