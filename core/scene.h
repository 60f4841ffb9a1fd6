// Scene data shared by every module: plain structs of arrays, no GL, no Embree.
//
// Conventions (../shared/DESIGN.md): right-handed, +Y up, cameras look down -Z,
// metres, linear scene-referred radiance in float.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_precision.hpp>

#include "core/animation.h"

namespace photovr {

// An image decoded to 8-bit RGBA as stored in the file. Whether it is sRGB-encoded is a
// property of the material slot that samples it (glTF 2.0 §3.9.2), not of the image.
struct Texture {
  std::string name;  // file name or generated name, for messages
  int width = 0;
  int height = 0;
  std::vector<uint8_t> rgba;  // width * height * 4, row 0 at the top (as in the file)
  enum class Wrap { Repeat, Clamp, Mirror } wrapS = Wrap::Repeat, wrapT = Wrap::Repeat;
  bool nearest = false;  // magnification filter NEAREST (else LINEAR, mipmapped)
};

// KHR_texture_transform: uv' = T(offset) * R(rotation) * S(scale) * uv.
struct TextureTransform {
  glm::vec2 offset{0.0f};
  float rotation = 0.0f;  // radians, counter-clockwise in UV space as the extension defines
  glm::vec2 scale{1.0f};
  glm::mat3 matrix() const;  // the 3x3 uv transform above
  bool isIdentity() const {
    return offset == glm::vec2(0.0f) && rotation == 0.0f && scale == glm::vec2(1.0f);
  }
};

struct TextureRef {
  int texture = -1;  // index into Scene::textures, -1 = none
  int texCoord = 0;  // TEXCOORD_n set (0 or 1)
  TextureTransform transform;
  bool valid() const { return texture >= 0; }
};

enum class AlphaMode { Opaque, Mask, Blend };

// glTF 2.0 metallic-roughness material (§3.9). Factors multiply the textures.
struct Material {
  std::string name;
  glm::vec4 baseColorFactor{1.0f};
  float metallicFactor = 1.0f;
  float roughnessFactor = 1.0f;  // perceptual roughness; alpha = roughness^2
  glm::vec3 emissiveFactor{0.0f};
  float emissiveStrength = 1.0f;  // KHR_materials_emissive_strength
  float normalScale = 1.0f;
  float occlusionStrength = 1.0f;
  AlphaMode alphaMode = AlphaMode::Opaque;
  float alphaCutoff = 0.5f;
  bool doubleSided = false;
  TextureRef baseColorTexture;          // sRGB
  TextureRef metallicRoughnessTexture;  // linear, B = metallic, G = roughness
  TextureRef normalTexture;             // linear, tangent space
  TextureRef occlusionTexture;          // linear, R
  TextureRef emissiveTexture;           // sRGB

  // KHR_materials_ior: the dielectric's index of refraction (1.5 in core glTF; 0 is the
  // extension's legacy value, reflectance 1 at normal incidence).
  float ior = 1.5f;
  // KHR_materials_specular: the dielectric layer's strength (both of glTF's dielectric_f0
  // and dielectric_f90) and the tint of its f0. 0 leaves a pure Lambert surface.
  float specularFactor = 1.0f;
  glm::vec3 specularColorFactor{1.0f};
  TextureRef specularTexture;       // linear, A = strength
  TextureRef specularColorTexture;  // sRGB, RGB = tint
  // KHR_materials_transmission: the share of the dielectric's diffuse lobe that is a rough
  // dielectric BTDF instead (glass, water).
  float transmissionFactor = 0.0f;
  TextureRef transmissionTexture;  // linear, R
  // KHR_materials_volume: thickness 0 is a thin-walled surface (light passes through
  // without bending); above 0 the mesh bounds a medium of this ior that absorbs by
  // Beer-Lambert with the attenuation colour reached after the attenuation distance.
  float thicknessFactor = 0.0f;
  glm::vec3 attenuationColor{1.0f};
  float attenuationDistance = 0.0f;  // 0 = infinite (no absorption), as the extension's default
  // KHR_materials_unlit: the surface shows its base colour (factor x texture) as radiance to
  // every ray and reflects nothing; not a light source for NEE (found by BSDF rays only).
  bool unlit = false;
  // KHR_materials_sheen: a fabric layer over the base (colour black = none).
  glm::vec3 sheenColorFactor{0.0f};
  float sheenRoughnessFactor = 0.0f;
  TextureRef sheenColorTexture;      // sRGB, RGB = colour
  TextureRef sheenRoughnessTexture;  // linear, A = roughness
  // KHR_materials_clearcoat: a clear dielectric coat (ior 1.5) over the sheen and base.
  float clearcoatFactor = 0.0f;
  float clearcoatRoughnessFactor = 0.0f;
  TextureRef clearcoatTexture;           // linear, R = strength
  TextureRef clearcoatRoughnessTexture;  // linear, G = roughness
  TextureRef clearcoatNormalTexture;     // linear, tangent space: the coat's own normal map
  float clearcoatNormalScale = 1.0f;

  glm::vec3 emission() const { return emissiveFactor * emissiveStrength; }
  bool isEmissive() const;
  // Every texture slot, set or not.
  std::array<const TextureRef*, 13> textureSlots() const {
    return {&baseColorTexture,      &metallicRoughnessTexture, &normalTexture,
            &occlusionTexture,      &emissiveTexture,          &specularTexture,
            &specularColorTexture,  &transmissionTexture,      &sheenColorTexture,
            &sheenRoughnessTexture, &clearcoatTexture,         &clearcoatRoughnessTexture,
            &clearcoatNormalTexture};
  }
  // Whether any slot is set: only then does a hit need its texture coordinates and tangent.
  bool textured() const;
  // ((ior - 1) / (ior + 1))^2, the dielectric's reflectance at normal incidence from air;
  // computed in double so the default ior gives exactly the float nearest 0.04.
  float iorF0() const;
  bool thinWalled() const { return !(thicknessFactor > 0.0f); }
  // Whether back faces are invisible (glTF 3.9.5: single-sided). A transmissive volume's
  // back faces are where light leaves it, so they stay whatever doubleSided says.
  bool cullsBackFaces() const {
    return !doubleSided && !(transmissionFactor > 0.0f && !thinWalled());
  }
  // Beer-Lambert's absorption coefficient inside the volume, per metre:
  // -ln(attenuationColor) / attenuationDistance; 0 for a thin wall or no absorption.
  glm::vec3 absorption() const;
};

// Linear-blend skinning data of a mesh a skinned node carries (glTF 2.0 §3.7.3): the bind
// pose and up to four joints per vertex (JOINTS_0 / WEIGHTS_0). core/skinning.h writes the
// mesh's positions, normals and tangents from them at each pose.
struct MeshSkinning {
  int skin = -1;  // index into Scene::skins; -1: a rigid mesh
  std::vector<glm::vec3> positions, normals;
  std::vector<glm::vec4> tangents;
  std::vector<glm::u16vec4> joints;  // indices into the skin's joints
  std::vector<glm::vec4> weights;    // non-negative, summing to 1
  // The skinned positions at the previous pose, for the G-buffer's motion vectors (a rigid
  // instance's come from Instance::previousTransform).
  std::vector<glm::vec3> previousPositions;
  double posedAt = std::numeric_limits<double>::quiet_NaN();  // the time 'positions' show
};

// One glTF primitive: a triangle list with one material. Stored once, referenced by
// any number of instances (a skinned one by its own instance only).
struct Mesh {
  std::string name;
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;   // per vertex, unit length; never empty after load
  std::vector<glm::vec4> tangents;  // xyz + handedness w; empty if no normal map needs it
  std::vector<glm::vec2> uv0;       // may be empty
  std::vector<glm::vec2> uv1;       // may be empty
  std::vector<uint32_t> indices;    // 3 per triangle, always present (generated if absent)
  int material = 0;                 // index into Scene::materials
  MeshSkinning skinning;            // read for every primitive with JOINTS_0, used when skinned

  size_t triangleCount() const { return indices.size() / 3; }
  bool skinned() const { return skinning.skin >= 0; }
  size_t vertexCount() const { return positions.size(); }
};

struct Instance {
  int mesh = 0;                       // index into Scene::meshes
  glm::mat4 transform{1.0f};          // object to world (a skinned mesh: identity)
  glm::mat4 previousTransform{1.0f};  // last frame's, for motion vectors
  std::string node;                   // glTF node name, for messages
};

// KHR_lights_punctual. Intensity units as the extension: candela for point and spot,
// lux for directional.
struct Light {
  enum class Type { Point, Spot, Directional } type = Type::Point;
  std::string name;
  glm::vec3 color{1.0f};
  float intensity = 1.0f;
  float range = 0.0f;  // 0 = infinite
  float innerConeAngle = 0.0f;
  float outerConeAngle = 0.78539816f;      // pi / 4, the extension's default
  glm::vec3 position{0.0f};                // world
  glm::vec3 direction{0.0f, 0.0f, -1.0f};  // world, the direction light travels
};

// A perspective camera. Pose is the camera-to-world rigid transform (looks down -Z).
struct Camera {
  std::string name;
  glm::vec3 position{0.0f};
  glm::quat orientation{1.0f, 0.0f, 0.0f, 0.0f};
  float yfov = 1.0f;    // radians
  float aspect = 0.0f;  // 0 = use the image's
  float znear = 0.05f;
  float zfar = 0.0f;  // 0 = infinite
};

// Equirectangular environment (latitude-linear, v = 1 at the top row), or a procedural
// sky for built-in scenes, or a constant. Radiance is linear.
struct Environment {
  enum class Type { None, Constant, Map, Sky } type = Type::None;
  std::string name;
  glm::vec3 constant{0.0f};
  float intensity = 1.0f;
  // Map
  int width = 0;
  int height = 0;
  std::vector<glm::vec3> pixels;  // width * height, row 0 at the top
  // Sky: a simple analytic gradient sky with a sun disc direction.
  glm::vec3 sunDirection{0.0f, 1.0f, 0.0f};  // towards the sun
  glm::vec3 zenithColor{0.0f};
  glm::vec3 horizonColor{0.0f};
  glm::vec3 groundColor{0.0f};
};

struct Bounds {
  glm::vec3 min{1e30f};
  glm::vec3 max{-1e30f};
  void extend(const glm::vec3& p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
  bool empty() const { return min.x > max.x; }
  glm::vec3 center() const { return 0.5f * (min + max); }
  glm::vec3 extent() const { return max - min; }
};

struct Scene {
  std::string name;  // built-in name or file path
  std::vector<Mesh> meshes;
  std::vector<Instance> instances;
  std::vector<Material> materials;
  std::vector<Texture> textures;
  std::vector<Light> lights;
  std::vector<Camera> cameras;
  Environment environment;
  std::vector<std::string> warnings;  // non-fatal problems found while loading
  // The file's extensionsUsed, each with whether photovr reads it (info lists them).
  struct Extension {
    std::string name;
    bool read = false;
  };
  std::vector<Extension> extensions;
  // The file's node hierarchy and its animations (core/animation.h): poseScene moves the
  // instances, lights and cameras the animated nodes carry. Empty for built-in scenes.
  std::vector<SceneNode> nodes;
  std::vector<Animation> animations;
  std::vector<Skin> skins;  // what skinned meshes (Mesh::skinning) are deformed by
  // Where this scene's coordinate zero lies in the coordinates of the file it came from
  // (metres, double): a far-away file is re-based near its content so that floats keep
  // their precision (core/scene_transform.h); translateScene keeps it up to date.
  glm::dvec3 origin{0.0};

  // Whether an instance's mesh index names a mesh (a broken scene may hold one that does not).
  bool hasMesh(int mesh) const { return mesh >= 0 && size_t(mesh) < meshes.size(); }
  size_t instancedTriangleCount() const;  // instances naming no mesh count nothing
  Bounds worldBounds() const;             // of the instances that name a mesh
};

}  // namespace photovr
