// The sheen lobe of KHR_materials_sheen: Estevez & Kulla, "Production Friendly Microfacet
// Sheen BRDF", SIGGRAPH 2017 course notes (see trace/bsdf.h, "The layers").
#include <algorithm>
#include <cmath>

#include "trace/bsdf.h"
#include "trace/sheen_albedo_table.h"

namespace photovr {
namespace {

// Estevez & Kulla's sec. 3 fit of ln Lambda(cos): a / (1 + b x^c) + d x + e, with each
// coefficient interpolated between its alpha = 0 and alpha = 1 values by (1 - alpha)^2.
float charlieL(float x, float alpha) {
  const float t = (1.0f - alpha) * (1.0f - alpha);
  const float a = 25.3245f * t + 21.5473f * (1.0f - t);
  const float b = 3.32435f * t + 3.82987f * (1.0f - t);
  const float c = 0.16801f * t + 0.19823f * (1.0f - t);
  const float d = -1.27393f * t + -1.97760f * (1.0f - t);
  const float e = -4.85967f * t + -4.32054f * (1.0f - t);
  return a / (1.0f + b * std::pow(x, c)) + d * x + e;
}

}  // namespace

float sheenRoughnessToAlpha(float sheenRoughness) {
  return roughnessToAlpha(sheenRoughness);  // the same square and floor as GGX's
}

float charlieD(const glm::vec3& h, float alpha) {
  const float sin2 = std::min(h.x * h.x + h.y * h.y, 1.0f);
  const float invAlpha = 1.0f / alpha;
  return (2.0f + invAlpha) * std::pow(sin2, 0.5f * invAlpha) * (0.5f * kInvPi);
}

float charlieLambda(float cosTheta, float alpha) {
  const float c = std::clamp(std::abs(cosTheta), 0.0f, 1.0f);
  if (c < 0.5f) return std::exp(charlieL(c, alpha));
  return std::exp(2.0f * charlieL(0.5f, alpha) - charlieL(1.0f - c, alpha));
}

float sheenBrdf(const glm::vec3& wo, const glm::vec3& wi, float alpha) {
  if (!(wo.z > 0.0f && wi.z > 0.0f)) return 0.0f;
  glm::vec3 h = wo + wi;
  const float len2 = glm::dot(h, h);
  if (!(len2 > 0.0f)) return 0.0f;
  h *= 1.0f / std::sqrt(len2);
  const float g = 1.0f / (1.0f + charlieLambda(wo.z, alpha) + charlieLambda(wi.z, alpha));
  return charlieD(h, alpha) * g / (4.0f * wo.z * wi.z);
}

float sheenAlbedo(float cosTheta, float sheenRoughness) {
  constexpr int n = kSheenAlbedoSize;
  const float x = std::sqrt(std::clamp(isFinite(cosTheta) ? cosTheta : 0.0f, 0.0f, 1.0f)) * (n - 1);
  const float y =
      std::clamp(isFinite(sheenRoughness) ? sheenRoughness : 0.0f, 0.0f, 1.0f) * (n - 1);
  const int x0 = std::min(int(x), n - 2), y0 = std::min(int(y), n - 2);
  const float fx = x - float(x0), fy = y - float(y0);
  const auto at = [](int i, int j) { return kSheenAlbedo[j][i]; };  // [roughness][sqrt(cos)]
  const float lo = at(x0, y0) + fx * (at(x0 + 1, y0) - at(x0, y0));
  const float hi = at(x0, y0 + 1) + fx * (at(x0 + 1, y0 + 1) - at(x0, y0 + 1));
  return lo + fy * (hi - lo);
}

}  // namespace photovr
