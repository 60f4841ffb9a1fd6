#include "trace/surface.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "trace/texture_sampling.h"

namespace photovr {
namespace {

// The vertex attributes at a hit besides its normal (HitGeometry::normal, from the
// geometry stage's lanes).
struct Interpolated {
  glm::vec4 tangent{0.0f};
  glm::vec2 uv0{0.0f}, uv1{0.0f};
};

template <typename T>
T lerp3(const std::vector<T>& a, const uint32_t* idx, float b0, float b1, float b2) {
  return b0 * a[idx[0]] + b1 * a[idx[1]] + b2 * a[idx[2]];
}

// Zero for an absent attribute.
template <typename T>
T attributeAt(const std::vector<T>& a, const uint32_t* idx, float b1, float b2) {
  return a.empty() ? T(0.0f) : lerp3(a, idx, 1.0f - b1 - b2, b1, b2);
}

Interpolated interpolate(const Mesh& m, const uint32_t* idx, float b1, float b2) {
  Interpolated r;
  r.tangent = attributeAt(m.tangents, idx, b1, b2);
  r.uv0 = attributeAt(m.uv0, idx, b1, b2);
  r.uv1 = attributeAt(m.uv1, idx, b1, b2);
  return r;
}

// glTF emission is one-sided for single-sided materials, two-sided for double-sided ones.
glm::vec3 emission(const Scene& scene, const Material& mat, glm::vec2 uv0, glm::vec2 uv1,
                   bool frontFace) {
  if (!frontFace && !mat.doubleSided) return glm::vec3(0.0f);
  if (mat.unlit)
    return glm::vec3(mat.baseColorFactor) *
           glm::vec3(sampleSlot(scene, mat.baseColorTexture, uv0, uv1, true, glm::vec4(1.0f)));
  return mat.emission() *
         glm::vec3(sampleSlot(scene, mat.emissiveTexture, uv0, uv1, true, glm::vec4(1.0f)));
}

glm::vec3 safeNormalize(const glm::vec3& v, const glm::vec3& fallback) {
  const float len = glm::length(v);
  return len > 0.0f && std::isfinite(len) ? v / len : fallback;
}

// Normal map 'map' with its scale in the interpolated tangent frame (glTF 3.9.3), as the
// G-buffer shader does.
glm::vec3 applyNormalMap(const Scene& scene, const TextureRef& map, float scale,
                         const Interpolated& in, const glm::mat4& transform, glm::vec3 n) {
  if (!map.valid() || glm::dot(glm::vec3(in.tangent), glm::vec3(in.tangent)) == 0.0f) return n;
  const glm::vec3 t0 = safeNormalize(glm::mat3(transform) * glm::vec3(in.tangent), glm::vec3(0.0f));
  const glm::vec3 t = safeNormalize(t0 - n * glm::dot(n, t0), glm::vec3(0.0f));
  if (t == glm::vec3(0.0f)) return n;
  const glm::vec3 b = glm::cross(n, t) * (in.tangent.w < 0.0f ? -1.0f : 1.0f);
  glm::vec3 tn =
      glm::vec3(sampleSlot(scene, map, in.uv0, in.uv1, false, glm::vec4(0.5f, 0.5f, 1.0f, 1.0f))) *
          2.0f -
      1.0f;
  tn.x *= scale;
  tn.y *= scale;
  return safeNormalize(tn.x * t + tn.y * b + tn.z * n, n);
}

// The coat's normal in the shading frame of 'h': its own map on the interpolated normal
// (not the base's map). Out of line, as most hits have no coat (measured alone, moving it
// out of surfaceAt changed nothing beyond noise; the coat normal's 2-3 % cost on scenes
// without coats is BsdfParams' larger size, docs/MEASUREMENTS.md).
[[gnu::noinline]] glm::vec3 coatNormalAt(const Scene& scene, const Material& mat,
                                         const Interpolated& in, const glm::mat4& transform,
                                         const glm::vec3& interpolated, const SurfaceHit& h) {
  glm::vec3 nc = applyNormalMap(scene, mat.clearcoatNormalTexture, mat.clearcoatNormalScale, in,
                                transform, interpolated);
  if (glm::dot(nc, h.geometricNormal) < 0.0f) nc = -nc;
  if (nc == h.shadingNormal) return {0.0f, 0.0f, 1.0f};
  return safeNormalize(Frame::fromZ(h.shadingNormal).toLocal(nc), {0, 0, 1});
}

// Reflects nothing: no diffuse, no specular (f0 = f90 = 0), no transmission.
BsdfParams unlitBsdf() {
  BsdfParams p{glm::vec3(0.0f), 0.0f, 1.0f};
  p.dielectricF0 = glm::vec3(0.0f);
  p.dielectricF90 = 0.0f;
  return p;
}

BsdfParams materialAt(const Scene& scene, const Material& mat, const Interpolated& in) {
  const glm::vec4 base = mat.baseColorFactor * sampleSlot(scene, mat.baseColorTexture, in.uv0,
                                                          in.uv1, true, glm::vec4(1.0f));
  const glm::vec4 mr =
      sampleSlot(scene, mat.metallicRoughnessTexture, in.uv0, in.uv1, false, glm::vec4(1.0f));
  BsdfParams p;
  p.baseColor = glm::clamp(glm::vec3(base), 0.0f, 1.0f);
  p.metallic = glm::clamp(mat.metallicFactor * mr.b, 0.0f, 1.0f);
  p.roughness = glm::clamp(mat.roughnessFactor * mr.g, 0.0f, 1.0f);
  // KHR_materials_specular's textures: strength in A, tint in sRGB RGB.
  const float strength =
      mat.specularFactor *
      sampleSlot(scene, mat.specularTexture, in.uv0, in.uv1, false, glm::vec4(1.0f)).a;
  const glm::vec3 tint =
      mat.specularColorFactor *
      glm::vec3(sampleSlot(scene, mat.specularColorTexture, in.uv0, in.uv1, true, glm::vec4(1.0f)));
  p.dielectricF0 = glm::min(mat.iorF0() * tint, glm::vec3(1.0f)) * strength;
  p.dielectricF90 = strength;
  if (mat.transmissionFactor > 0.0f)
    p.transmission =
        mat.transmissionFactor *
        sampleSlot(scene, mat.transmissionTexture, in.uv0, in.uv1, false, glm::vec4(1.0f)).r;
  p.thinWalled = mat.thinWalled();
  p.eta = mat.ior;
  // KHR_materials_sheen (colour sRGB RGB, roughness A) and _clearcoat (strength R,
  // roughness G), each texture only where its factor can show.
  if (mat.sheenColorFactor != glm::vec3(0.0f)) {
    p.sheenColor = mat.sheenColorFactor * glm::vec3(sampleSlot(scene, mat.sheenColorTexture, in.uv0,
                                                               in.uv1, true, glm::vec4(1.0f)));
    p.sheenRoughness =
        mat.sheenRoughnessFactor *
        sampleSlot(scene, mat.sheenRoughnessTexture, in.uv0, in.uv1, false, glm::vec4(1.0f)).a;
  }
  if (mat.clearcoatFactor > 0.0f) {
    p.clearcoat = mat.clearcoatFactor *
                  sampleSlot(scene, mat.clearcoatTexture, in.uv0, in.uv1, false, glm::vec4(1.0f)).r;
    p.clearcoatRoughness =
        mat.clearcoatRoughnessFactor *
        sampleSlot(scene, mat.clearcoatRoughnessTexture, in.uv0, in.uv1, false, glm::vec4(1.0f)).g;
  }
  if (mat.unlit) p = unlitBsdf();
  return p;
}

// What every hit gets: position and its error bound, the geometric normal facing the ray
// and the side it hit, from the hit's geometry (trace/hit_geometry.h).
SurfaceHit fromGeometry(const HitRef& ref, const HitGeometry& g, const glm::vec3& incoming) {
  SurfaceHit h;
  h.instance = ref.instance;
  h.triangle = ref.triangle;
  h.position = g.position;
  h.positionError = g.positionError;
  h.frontFace = glm::dot(g.ng, incoming) < 0.0f;
  h.geometricNormal = h.frontFace ? g.ng : -g.ng;
  return h;
}

// surfaceAt, with 'constant' the material's table entry where it has one (untextured).
SurfaceHit shadeSurface(const Scene& scene, const ConstantMaterial* constant, const HitRef& ref,
                        const HitGeometry& g, const glm::vec3& incoming) {
  SurfaceHit h = fromGeometry(ref, g, incoming);
  const Instance& inst = scene.instances[ref.instance];
  const Mesh& mesh = scene.meshes[inst.mesh];
  const Material& mat = scene.materials[mesh.material];
  const glm::mat4& m = inst.transform;
  const glm::vec3& interpolated = g.normal;
  // Shading normal on the viewer's side of the geometry (back faces of double-sided
  // materials shade with the flipped normal, glTF 3.9.6).
  const auto facing = [&](glm::vec3 n) { return glm::dot(n, h.geometricNormal) < 0.0f ? -n : n; };
  Interpolated in;
  if (constant) {
    h.shadingNormal = facing(interpolated);
    h.bsdf = constant->bsdf;
    h.emission = constant->emission[h.frontFace];
  } else {
    // Texture coordinates and tangents only where a texture reads them: interpolating the
    // first set was a third of surfaceAt's time on spheres, which has no texture.
    if (mat.textured())
      in = interpolate(mesh, &mesh.indices[3 * size_t(ref.triangle)], ref.b1, ref.b2);
    // Only where there is a map: the call alone, to return 'interpolated', was 2 % of
    // cornell's tracer (its result waited on through the stack frame's teardown).
    h.shadingNormal =
        facing(mat.normalTexture.valid()
                   ? applyNormalMap(scene, mat.normalTexture, mat.normalScale, in, m, interpolated)
                   : interpolated);
    h.bsdf = materialAt(scene, mat, in);
    h.emission = emission(scene, mat, in.uv0, in.uv1, h.frontFace);
  }
  if (h.bsdf.clearcoat > 0.0f) h.bsdf.coatNormal = coatNormalAt(scene, mat, in, m, interpolated, h);
  // A volume's interface: entering from the front, leaving from the back.
  if (!h.bsdf.thinWalled && !h.frontFace && h.bsdf.eta > 0.0f) h.bsdf.eta = 1.0f / h.bsdf.eta;
  return h;
}

}  // namespace

MaterialTable::MaterialTable(const Scene& scene)
    : constants_(scene.materials.size()), constant_(scene.materials.size(), 0) {
  for (size_t i = 0; i < scene.materials.size(); ++i) {
    const Material& mat = scene.materials[i];
    if (mat.textured()) continue;
    constant_[i] = 1;
    constants_[i].bsdf = materialAt(scene, mat, Interpolated{});
    for (const bool front : {false, true})
      constants_[i].emission[front] = emission(scene, mat, {}, {}, front);
  }
}

SurfaceHit surfaceAt(const Scene& scene, const HitRef& ref, const HitGeometry& g,
                     const glm::vec3& incoming) {
  return shadeSurface(scene, nullptr, ref, g, incoming);
}

SurfaceHit surfaceAt(const Scene& scene, const MaterialTable& materials, const HitRef& ref,
                     const HitGeometry& g, const glm::vec3& incoming) {
  const uint32_t material = uint32_t(scene.meshes[scene.instances[ref.instance].mesh].material);
  return shadeSurface(scene, materials.constantOf(material), ref, g, incoming);
}

SurfaceHit surfaceAt(const Scene& scene, uint32_t instance, uint32_t triangle, float b1, float b2,
                     const glm::vec3& incoming) {
  const HitRef ref{instance, triangle, b1, b2};
  return surfaceAt(scene, ref, hitGeometry(scene, ref), incoming);
}

SurfaceHit surfaceEmissionAt(const Scene& scene, const HitRef& ref, const HitGeometry& g,
                             const glm::vec3& incoming) {
  SurfaceHit h = fromGeometry(ref, g, incoming);
  h.emission = emissionAt(scene, ref.instance, ref.triangle, ref.b1, ref.b2, g.ng, incoming);
  return h;
}

SurfaceHit surfaceEmissionAt(const Scene& scene, uint32_t instance, uint32_t triangle, float b1,
                             float b2, const glm::vec3& incoming) {
  const HitRef ref{instance, triangle, b1, b2};
  return surfaceEmissionAt(scene, ref, hitGeometry(scene, ref), incoming);
}

glm::vec3 unitGeometricNormal(const glm::vec3& e1, const glm::vec3& e2) {
  return safeNormalize(glm::cross(e1, e2), glm::vec3(0, 1, 0));
}

glm::vec3 emissionAt(const Scene& scene, uint32_t instance, uint32_t triangle, float b1, float b2,
                     const glm::vec3& geometricNormal, const glm::vec3& incoming) {
  const Mesh& mesh = scene.meshes[scene.instances[instance].mesh];
  const Material& mat = scene.materials[mesh.material];
  const bool frontFace = glm::dot(geometricNormal, incoming) < 0.0f;
  const TextureRef& texture = mat.unlit ? mat.baseColorTexture : mat.emissiveTexture;
  if (!texture.valid()) return emission(scene, mat, {}, {}, frontFace);
  const uint32_t* idx = &mesh.indices[3 * size_t(triangle)];
  return emission(scene, mat, attributeAt(mesh.uv0, idx, b1, b2),
                  attributeAt(mesh.uv1, idx, b1, b2), frontFace);
}

float surfaceAlpha(const Scene& scene, const Mesh& mesh, const Material& material,
                   uint32_t triangle, float b1, float b2) {
  const uint32_t* idx = &mesh.indices[3 * size_t(triangle)];
  const glm::vec4 base = material.baseColorFactor * sampleSlot(scene, material.baseColorTexture,
                                                               attributeAt(mesh.uv0, idx, b1, b2),
                                                               attributeAt(mesh.uv1, idx, b1, b2),
                                                               true, glm::vec4(1.0f));
  return base.a;
}

float coverageAt(const Scene& scene, uint32_t instance, uint32_t triangle, float b1, float b2) {
  const Mesh& mesh = scene.meshes[scene.instances[instance].mesh];
  const Material& mat = scene.materials[mesh.material];
  if (mat.alphaMode == AlphaMode::Opaque) return 1.0f;
  const float alpha = surfaceAlpha(scene, mesh, mat, triangle, b1, b2);
  if (mat.alphaMode == AlphaMode::Mask) return alpha < mat.alphaCutoff ? 0.0f : 1.0f;
  return std::clamp(alpha, 0.0f, 1.0f);
}

glm::vec3 emittedRadiance(const Scene&, const SurfaceHit& hit) {
  return hit.emission;
}

glm::vec3 offsetRayOrigin(const SurfaceHit& hit, const glm::vec3& dir) {
  // Leave on the side the new ray travels to.
  const glm::vec3 n =
      glm::dot(dir, hit.geometricNormal) >= 0.0f ? hit.geometricNormal : -hit.geometricNormal;
  // Wachter & Binder 2019, listing 6-1: origin = 1/32, int_scale = 256. Their near-origin
  // branch adds an absolute float_scale = 1/65536 m; photovr adds the hit's own error bound
  // there instead, which scales with the geometry: the absolute 1.5e-5 m is 0.75 % of a
  // 2 mm scene and leaked light through its 1 um gaps (stress suite, "scaled 1e-3").
  constexpr float kOrigin = 1.0f / 32.0f, kIntScale = 256.0f;
  const glm::vec3 p = hit.position + n * hit.positionError;
  glm::vec3 out;
  for (int k = 0; k < 3; ++k) {
    const int offset = int(kIntScale * n[k]);
    int32_t bits;
    std::memcpy(&bits, &p[k], sizeof bits);
    bits += (p[k] < 0.0f) ? -offset : offset;
    float moved;
    std::memcpy(&moved, &bits, sizeof moved);
    out[k] = std::abs(p[k]) < kOrigin ? p[k] + 2.0f * hit.positionError * n[k] : moved;
  }
  return out;
}

}  // namespace photovr
