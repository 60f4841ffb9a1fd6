#include "core/scene_hash.h"

#include <cstdio>

namespace photovr {

Hasher& Hasher::bytes(const void* data, size_t size) {
  // FNV-1a (Fowler, Noll, Vo): simple, no dependency; collisions are irrelevant at the
  // handful of cached references a machine holds.
  const auto* p = static_cast<const uint8_t*>(data);
  for (size_t i = 0; i < size; ++i) state_ = (state_ ^ p[i]) * 0x100000001b3ull;
  return *this;
}

static void hashMaterial(Hasher& h, const Material& m) {
  h.value(m.baseColorFactor).value(m.metallicFactor).value(m.roughnessFactor);
  h.value(m.emissiveFactor).value(m.emissiveStrength).value(m.normalScale);
  h.value(m.occlusionStrength).value(m.alphaMode).value(m.alphaCutoff).value(m.doubleSided);
  h.value(m.ior).value(m.specularFactor).value(m.specularColorFactor);
  h.value(m.transmissionFactor).value(m.thicknessFactor).value(m.attenuationColor);
  h.value(m.attenuationDistance).value(m.unlit);
  h.value(m.sheenColorFactor).value(m.sheenRoughnessFactor);
  h.value(m.clearcoatFactor).value(m.clearcoatRoughnessFactor).value(m.clearcoatNormalScale);
  for (const TextureRef* r : m.textureSlots())
    h.value(r->texture)
        .value(r->texCoord)
        .value(r->transform.offset)
        .value(r->transform.rotation)
        .value(r->transform.scale);
}

uint64_t hashScene(const Scene& s) {
  Hasher h;
  for (const Mesh& m : s.meshes)
    h.vector(m.positions)
        .vector(m.normals)
        .vector(m.tangents)
        .vector(m.uv0)
        .vector(m.uv1)
        .vector(m.indices)
        .value(m.material);
  for (const Instance& i : s.instances) h.value(i.mesh).value(i.transform);
  for (const Material& m : s.materials) hashMaterial(h, m);
  for (const Texture& t : s.textures)
    h.value(t.width).value(t.height).vector(t.rgba).value(t.wrapS).value(t.wrapT).value(t.nearest);
  for (const Light& l : s.lights)
    h.value(l.type)
        .value(l.color)
        .value(l.intensity)
        .value(l.range)
        .value(l.innerConeAngle)
        .value(l.outerConeAngle)
        .value(l.position)
        .value(l.direction);
  const Environment& e = s.environment;
  h.value(e.type)
      .value(e.constant)
      .value(e.intensity)
      .value(e.width)
      .value(e.height)
      .vector(e.pixels);
  h.value(e.sunDirection).value(e.zenithColor).value(e.horizonColor).value(e.groundColor);
  return h.digest();
}

std::string hexDigest(uint64_t v) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", (unsigned long long)v);
  return buf;
}

}  // namespace photovr
