#include "core/gltf_writer.h"

#include <tiny_gltf.h>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <sstream>

#include <glm/gtc/type_ptr.hpp>

#include "core/files.h"
#include "core/error.h"

namespace photovr {
namespace {

namespace fs = std::filesystem;
namespace tg = tinygltf;

// Vertex arrays are copied straight into the buffer, so glm must not pad them.
static_assert(sizeof(glm::vec2) == 8 && sizeof(glm::vec3) == 12 && sizeof(glm::vec4) == 16);

struct Writer {
  const Scene& scene;
  std::string path;
  tg::Model model;
  bool usesTextureTransform = false;
  std::vector<std::string> materialExtensions{};  // declared in extensionsUsed, in first-use order
  int originNode = -1;  // the node every other hangs from when the scene was re-based

  [[noreturn]] void fail(const std::string& problem) const { throw InputError(path, problem); }
  std::vector<unsigned char>& bin() { return model.buffers[0].data; }
};

// ---------------------------------------------------------------------------------------
// Buffer data (glTF 2.0 §3.6)

int addView(Writer& w, const void* data, size_t bytes, int target) {
  std::vector<unsigned char>& bin = w.bin();
  bin.resize((bin.size() + 3) & ~size_t(3));  // §3.6.2.4: 4-byte alignment suits every type
  tg::BufferView view;
  view.buffer = 0;
  view.byteOffset = bin.size();
  view.byteLength = bytes;
  view.target = target;
  const unsigned char* p = static_cast<const unsigned char*>(data);
  bin.insert(bin.end(), p, p + bytes);
  w.model.bufferViews.push_back(view);
  return int(w.model.bufferViews.size() - 1);
}

template <typename T>
int addAccessor(Writer& w, const std::vector<T>& values, int componentType, int type, int target) {
  tg::Accessor accessor;
  accessor.bufferView = addView(w, values.data(), values.size() * sizeof(T), target);
  accessor.componentType = componentType;
  accessor.count = values.size();
  accessor.type = type;
  w.model.accessors.push_back(accessor);
  return int(w.model.accessors.size() - 1);
}

// §3.7.2.1: the POSITION accessor must carry min and max.
void setBounds(tg::Accessor& accessor, const std::vector<glm::vec3>& positions) {
  glm::vec3 lo(positions[0]), hi(positions[0]);
  for (const glm::vec3& p : positions) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  accessor.minValues = {lo.x, lo.y, lo.z};
  accessor.maxValues = {hi.x, hi.y, hi.z};
}

void addMesh(Writer& w, const Mesh& mesh) {
  if (mesh.positions.empty() || mesh.indices.empty())
    w.fail("mesh '" + mesh.name + "' has no triangles to write");
  const int vertexTarget = TINYGLTF_TARGET_ARRAY_BUFFER;
  tg::Primitive prim;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  prim.material = mesh.material;
  const int position = addAccessor(w, mesh.positions, TINYGLTF_COMPONENT_TYPE_FLOAT,
                                   TINYGLTF_TYPE_VEC3, vertexTarget);
  setBounds(w.model.accessors[size_t(position)], mesh.positions);
  prim.attributes["POSITION"] = position;
  const auto add = [&](const char* name, const auto& values, int type) {
    if (!values.empty())
      prim.attributes[name] =
          addAccessor(w, values, TINYGLTF_COMPONENT_TYPE_FLOAT, type, vertexTarget);
  };
  add("NORMAL", mesh.normals, TINYGLTF_TYPE_VEC3);
  add("TANGENT", mesh.tangents, TINYGLTF_TYPE_VEC4);
  add("TEXCOORD_0", mesh.uv0, TINYGLTF_TYPE_VEC2);
  add("TEXCOORD_1", mesh.uv1, TINYGLTF_TYPE_VEC2);
  prim.indices = addAccessor(w, mesh.indices, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT,
                             TINYGLTF_TYPE_SCALAR, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  tg::Mesh out;
  out.name = mesh.name;
  out.primitives.push_back(prim);
  w.model.meshes.push_back(out);
}

// ---------------------------------------------------------------------------------------
// Textures, embedded as PNG in the binary buffer

std::vector<unsigned char> encodePng(const Writer& w, const Texture& t) {
  if (t.width <= 0 || t.height <= 0 || t.rgba.size() != size_t(t.width) * t.height * 4)
    w.fail("texture '" + t.name + "' has no valid RGBA8 pixels to write");
  std::vector<unsigned char> png;
  OIIO::Filesystem::IOVecOutput memory(png);
  void* proxy = &memory;
  OIIO::ImageSpec spec(t.width, t.height, 4, OIIO::TypeDesc::UINT8);
  spec.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
  // glTF colours are straight alpha (§3.9.2); without this OpenImageIO would divide the
  // colour by alpha before encoding.
  spec.attribute("oiio:UnassociatedAlpha", 1);
  auto out = OIIO::ImageOutput::create("png");
  const bool ok = out && out->open("texture.png", spec) &&
                  out->write_image(OIIO::TypeDesc::UINT8, t.rgba.data()) && out->close();
  if (!ok)
    w.fail("texture '" + t.name +
           "': cannot encode PNG: " + (out ? out->geterror() : OIIO::geterror()));
  return png;
}

int samplerWrap(Texture::Wrap wrap) {
  switch (wrap) {
    case Texture::Wrap::Clamp:
      return TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
    case Texture::Wrap::Mirror:
      return TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT;
    default:
      return TINYGLTF_TEXTURE_WRAP_REPEAT;
  }
}

// One image, sampler and texture per photovr texture, so indices stay the same.
void addTexture(Writer& w, const Texture& t) {
  const std::vector<unsigned char> png = encodePng(w, t);
  tg::Image image;
  image.name = t.name;
  image.mimeType = "image/png";
  image.bufferView = addView(w, png.data(), png.size(), 0);
  w.model.images.push_back(image);
  tg::Sampler sampler;
  sampler.wrapS = samplerWrap(t.wrapS);
  sampler.wrapT = samplerWrap(t.wrapT);
  sampler.magFilter = t.nearest ? TINYGLTF_TEXTURE_FILTER_NEAREST : TINYGLTF_TEXTURE_FILTER_LINEAR;
  w.model.samplers.push_back(sampler);
  tg::Texture texture;
  texture.name = t.name;
  texture.source = int(w.model.images.size() - 1);
  texture.sampler = int(w.model.samplers.size() - 1);
  w.model.textures.push_back(texture);
}

// ---------------------------------------------------------------------------------------
// Materials (glTF 2.0 §3.9)

tg::Value numbers(std::initializer_list<float> values) {
  tg::Value::Array array;
  for (float v : values) array.push_back(tg::Value(double(v)));
  return tg::Value(array);
}

tg::Value transformValue(const TextureTransform& t) {
  tg::Value::Object object;
  object["offset"] = numbers({t.offset.x, t.offset.y});
  object["rotation"] = tg::Value(double(t.rotation));
  object["scale"] = numbers({t.scale.x, t.scale.y});
  return tg::Value(object);
}

template <typename Info>
void setTexture(Writer& w, Info& info, const TextureRef& ref, const std::string& material) {
  if (!ref.valid()) return;
  if (size_t(ref.texture) >= w.scene.textures.size())
    w.fail("material '" + material + "' references missing texture " + std::to_string(ref.texture));
  info.index = ref.texture;
  info.texCoord = ref.texCoord;
  if (ref.transform.isIdentity()) return;
  info.extensions["KHR_texture_transform"] = transformValue(ref.transform);
  w.usesTextureTransform = true;
}

void addExtension(Writer& w, tg::Material& out, const std::string& name, tg::Value::Object fields) {
  out.extensions[name] = tg::Value(std::move(fields));
  if (std::find(w.materialExtensions.begin(), w.materialExtensions.end(), name) ==
      w.materialExtensions.end())
    w.materialExtensions.push_back(name);
}

const char* alphaModeName(AlphaMode mode) {
  switch (mode) {
    case AlphaMode::Mask:
      return "MASK";
    case AlphaMode::Blend:
      return "BLEND";
    default:
      return "OPAQUE";
  }
}

void setFactors(Writer& w, const Material& m, tg::Material& out) {
  const glm::vec4& c = m.baseColorFactor;
  out.pbrMetallicRoughness.baseColorFactor = {c.r, c.g, c.b, c.a};
  out.pbrMetallicRoughness.metallicFactor = m.metallicFactor;
  out.pbrMetallicRoughness.roughnessFactor = m.roughnessFactor;
  out.emissiveFactor = {m.emissiveFactor.r, m.emissiveFactor.g, m.emissiveFactor.b};
  out.normalTexture.scale = m.normalScale;
  out.occlusionTexture.strength = m.occlusionStrength;
  out.alphaMode = alphaModeName(m.alphaMode);
  out.alphaCutoff = m.alphaCutoff;
  out.doubleSided = m.doubleSided;
  if (m.emissiveStrength != 1.0f)
    addExtension(w, out, "KHR_materials_emissive_strength",
                 {{"emissiveStrength", tg::Value(double(m.emissiveStrength))}});
}

tg::Value vec3Value(const glm::vec3& v) {
  return numbers({v.x, v.y, v.z});
}

// A textureInfo inside an extension, as setTexture writes the core ones.
// 'scale': a normal texture's (written where it is not glTF's default 1).
void addTextureValue(Writer& w, tg::Value::Object& ext, const char* key, const TextureRef& ref,
                     const std::string& material, float scale = 1.0f) {
  if (!ref.valid()) return;
  tg::TextureInfo info;
  setTexture(w, info, ref, material);
  tg::Value::Object o;
  o["index"] = tg::Value(info.index);
  if (info.texCoord != 0) o["texCoord"] = tg::Value(info.texCoord);
  if (scale != 1.0f) o["scale"] = tg::Value(double(scale));
  if (!info.extensions.empty()) {
    tg::Value::Object e(info.extensions.begin(), info.extensions.end());
    o["extensions"] = tg::Value(e);
  }
  ext[key] = tg::Value(o);
}

// KHR_materials_ior, _specular, _transmission, _unlit, _sheen, _clearcoat and _volume, each
// only where it differs from
// the core model (the loader's defaults).
void setDielectric(Writer& w, const Material& m, tg::Material& out) {
  const Material core;
  if (m.ior != core.ior)
    addExtension(w, out, "KHR_materials_ior", {{"ior", tg::Value(double(m.ior))}});
  if (m.specularFactor != core.specularFactor ||
      m.specularColorFactor != core.specularColorFactor || m.specularTexture.valid() ||
      m.specularColorTexture.valid()) {
    tg::Value::Object e{{"specularFactor", tg::Value(double(m.specularFactor))},
                        {"specularColorFactor", vec3Value(m.specularColorFactor)}};
    addTextureValue(w, e, "specularTexture", m.specularTexture, m.name);
    addTextureValue(w, e, "specularColorTexture", m.specularColorTexture, m.name);
    addExtension(w, out, "KHR_materials_specular", std::move(e));
  }
  if (m.transmissionFactor != core.transmissionFactor || m.transmissionTexture.valid()) {
    tg::Value::Object e{{"transmissionFactor", tg::Value(double(m.transmissionFactor))}};
    addTextureValue(w, e, "transmissionTexture", m.transmissionTexture, m.name);
    addExtension(w, out, "KHR_materials_transmission", std::move(e));
  }
  if (m.unlit) addExtension(w, out, "KHR_materials_unlit", {});
  if (m.sheenColorFactor != core.sheenColorFactor || m.sheenColorTexture.valid() ||
      m.sheenRoughnessFactor != core.sheenRoughnessFactor || m.sheenRoughnessTexture.valid()) {
    tg::Value::Object e{{"sheenColorFactor", vec3Value(m.sheenColorFactor)},
                        {"sheenRoughnessFactor", tg::Value(double(m.sheenRoughnessFactor))}};
    addTextureValue(w, e, "sheenColorTexture", m.sheenColorTexture, m.name);
    addTextureValue(w, e, "sheenRoughnessTexture", m.sheenRoughnessTexture, m.name);
    addExtension(w, out, "KHR_materials_sheen", std::move(e));
  }
  if (m.clearcoatFactor != core.clearcoatFactor || m.clearcoatTexture.valid() ||
      m.clearcoatRoughnessFactor != core.clearcoatRoughnessFactor ||
      m.clearcoatRoughnessTexture.valid() || m.clearcoatNormalTexture.valid()) {
    tg::Value::Object e{
        {"clearcoatFactor", tg::Value(double(m.clearcoatFactor))},
        {"clearcoatRoughnessFactor", tg::Value(double(m.clearcoatRoughnessFactor))}};
    addTextureValue(w, e, "clearcoatTexture", m.clearcoatTexture, m.name);
    addTextureValue(w, e, "clearcoatRoughnessTexture", m.clearcoatRoughnessTexture, m.name);
    addTextureValue(w, e, "clearcoatNormalTexture", m.clearcoatNormalTexture, m.name,
                    m.clearcoatNormalScale);
    addExtension(w, out, "KHR_materials_clearcoat", std::move(e));
  }
  if (!m.thinWalled()) {
    tg::Value::Object e{{"thicknessFactor", tg::Value(double(m.thicknessFactor))},
                        {"attenuationColor", vec3Value(m.attenuationColor)}};
    if (m.attenuationDistance > 0.0f)
      e["attenuationDistance"] = tg::Value(double(m.attenuationDistance));
    addExtension(w, out, "KHR_materials_volume", std::move(e));
  }
}

void addMaterial(Writer& w, const Material& m) {
  tg::Material out;
  out.name = m.name;
  setFactors(w, m, out);
  setDielectric(w, m, out);
  setTexture(w, out.pbrMetallicRoughness.baseColorTexture, m.baseColorTexture, m.name);
  setTexture(w, out.pbrMetallicRoughness.metallicRoughnessTexture, m.metallicRoughnessTexture,
             m.name);
  setTexture(w, out.normalTexture, m.normalTexture, m.name);
  setTexture(w, out.occlusionTexture, m.occlusionTexture, m.name);
  setTexture(w, out.emissiveTexture, m.emissiveTexture, m.name);
  w.model.materials.push_back(out);
}

// ---------------------------------------------------------------------------------------
// Nodes: instances, lights, cameras (glTF 2.0 §3.5)

int addNode(Writer& w, tg::Node node) {
  w.model.nodes.push_back(std::move(node));
  const int index = int(w.model.nodes.size() - 1);
  if (w.originNode >= 0)
    w.model.nodes[size_t(w.originNode)].children.push_back(index);
  else
    w.model.scenes[0].nodes.push_back(index);
  return index;
}

// A scene re-based away from its file's zero (Scene::origin) is written back where it was:
// one root node carries the origin as a translation, in double as glTF stores it.
void addOriginNode(Writer& w) {
  if (w.scene.origin == glm::dvec3(0.0)) return;
  tg::Node node;
  node.name = "photovr origin";
  node.translation = {w.scene.origin.x, w.scene.origin.y, w.scene.origin.z};
  w.model.nodes.push_back(std::move(node));
  w.originNode = int(w.model.nodes.size() - 1);
  w.model.scenes[0].nodes.push_back(w.originNode);
}

void addInstance(Writer& w, const Instance& instance) {
  if (instance.mesh < 0 || size_t(instance.mesh) >= w.scene.meshes.size())
    w.fail("instance '" + instance.node + "' references missing mesh " +
           std::to_string(instance.mesh));
  tg::Node node;
  node.name = instance.node;
  node.mesh = instance.mesh;  // glTF mesh i is photovr mesh i, so instances share meshes
  if (instance.transform != glm::mat4(1.0f)) {
    const float* m = glm::value_ptr(instance.transform);  // both column-major
    node.matrix.assign(m, m + 16);
  }
  addNode(w, node);
}

// The rotation taking the node's -Z (KHR_lights_punctual's light direction) onto 'to':
// the half-way quaternion (1 + a.b, a x b), normalised.
glm::quat rotationFromMinusZ(glm::vec3 to) {
  const glm::vec3 from(0.0f, 0.0f, -1.0f);
  to = glm::normalize(to);
  const float c = glm::dot(from, to);
  if (c < -0.999999f) return glm::quat(0.0f, 0.0f, 1.0f, 0.0f);  // half turn about +Y
  const glm::vec3 axis = glm::cross(from, to);
  return glm::normalize(glm::quat(1.0f + c, axis.x, axis.y, axis.z));
}

void setPose(tg::Node& node, const glm::vec3& position, const glm::quat& q) {
  node.translation = {position.x, position.y, position.z};
  node.rotation = {q.x, q.y, q.z, q.w};  // glTF order: x, y, z, w
}

const char* lightTypeName(Light::Type type) {
  switch (type) {
    case Light::Type::Spot:
      return "spot";
    case Light::Type::Directional:
      return "directional";
    default:
      return "point";
  }
}

void addLight(Writer& w, const Light& light) {
  tg::Light out;
  out.name = light.name;
  out.type = lightTypeName(light.type);
  out.color = {light.color.r, light.color.g, light.color.b};
  out.intensity = light.intensity;
  out.range = light.range;
  out.spot.innerConeAngle = light.innerConeAngle;
  out.spot.outerConeAngle = light.outerConeAngle;
  w.model.lights.push_back(out);
  tg::Node node;
  node.name = light.name;
  setPose(node, light.position, rotationFromMinusZ(light.direction));
  tg::Value::Object ref;
  ref["light"] = tg::Value(int(w.model.lights.size() - 1));
  node.extensions["KHR_lights_punctual"] = tg::Value(ref);
  addNode(w, node);
}

void addCamera(Writer& w, const Camera& camera) {
  tg::Camera out;
  out.name = camera.name;
  out.type = "perspective";
  out.perspective.yfov = camera.yfov;
  out.perspective.aspectRatio = camera.aspect;
  out.perspective.znear = camera.znear;
  out.perspective.zfar = camera.zfar;
  w.model.cameras.push_back(out);
  tg::Node node;
  node.name = camera.name;
  node.camera = int(w.model.cameras.size() - 1);
  setPose(node, camera.position, camera.orientation);
  addNode(w, node);
}

// ---------------------------------------------------------------------------------------
// Assembly and the atomic write

void declareExtensions(Writer& w) {
  // KHR_lights_punctual is declared by tinygltf's serializer when lights exist.
  if (w.usesTextureTransform) w.model.extensionsUsed.push_back("KHR_texture_transform");
  for (const std::string& name : w.materialExtensions) w.model.extensionsUsed.push_back(name);
}

void buildModel(Writer& w) {
  w.model.asset.version = "2.0";
  w.model.asset.generator = "photovr";
  w.model.buffers.resize(1);
  w.model.scenes.resize(1);
  w.model.defaultScene = 0;
  for (const Texture& t : w.scene.textures) addTexture(w, t);
  for (const Material& m : w.scene.materials) addMaterial(w, m);
  for (const Mesh& mesh : w.scene.meshes) {
    if (mesh.material < 0 || size_t(mesh.material) >= w.scene.materials.size())
      w.fail("mesh '" + mesh.name + "' references missing material " +
             std::to_string(mesh.material));
    addMesh(w, mesh);
  }
  addOriginNode(w);
  for (const Instance& instance : w.scene.instances) addInstance(w, instance);
  for (const Light& light : w.scene.lights) addLight(w, light);
  for (const Camera& camera : w.scene.cameras) addCamera(w, camera);
  if (w.bin().empty()) w.model.buffers.clear();  // §3.6.1: a buffer has byteLength >= 1
  declareExtensions(w);
}

std::string lowerExtension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

// tinygltf always writes a perspective camera's zfar, as 0 for an infinite one, which glTF
// 2.0 forbids (§5.13: zfar > 0 when present; left out = infinite). It is dropped from the
// JSON. tinygltf sorts members, so the one after zfar (znear, always written) follows it.
// Length of the member at 'at' if it is an infinite zfar ("zfar": 0 or 0.0, with the comma
// and spaces after it), else 0.
size_t infiniteZfarLength(const std::string& j, size_t at) {
  size_t i = at + 6;  // past "zfar"
  const auto skipSpaces = [&] {
    while (i < j.size() && std::isspace(static_cast<unsigned char>(j[i]))) ++i;
  };
  const auto take = [&](char c) { return i < j.size() && j[i] == c ? (++i, true) : false; };
  skipSpaces();
  if (!take(':')) return 0;
  skipSpaces();
  if (!take('0')) return 0;
  if (take('.')) {
    while (take('0')) continue;
  }
  skipSpaces();
  if (!take(',')) return 0;
  skipSpaces();
  return i - at;
}

std::string withoutInfiniteZfar(const std::string& json) {
  std::string out;
  size_t from = 0;
  for (size_t at; (at = json.find("\"zfar\"", from)) != std::string::npos;) {
    const size_t n = infiniteZfarLength(json, at);
    out.append(json, from, at - from + (n ? 0 : 6));  // a finite zfar is kept
    from = at + (n ? n : 6);
  }
  return out + json.substr(from);
}

uint32_t readLe32(const std::string& s, size_t at) {
  uint32_t v = 0;
  for (int i = 3; i >= 0; --i) v = (v << 8) | uint8_t(s[at + size_t(i)]);
  return v;
}

void writeLe32(std::string& s, size_t at, uint32_t v) {
  for (int i = 0; i < 4; ++i) s[at + size_t(i)] = char((v >> (8 * i)) & 0xff);
}

// The same in a GLB (§4.4): its first chunk is the JSON, padded with spaces to 4 bytes;
// the container's and the chunk's lengths follow the new JSON.
std::string glbWithoutInfiniteZfar(const std::string& glb, const Writer& w) {
  if (glb.size() < 20 || readLe32(glb, 16) != 0x4E4F534Au) w.fail("malformed GLB from tinygltf");
  const size_t jsonLength = readLe32(glb, 12);
  if (20 + jsonLength > glb.size()) w.fail("malformed GLB from tinygltf");
  std::string json = withoutInfiniteZfar(glb.substr(20, jsonLength));
  while (json.size() % 4) json += ' ';
  std::string out = glb.substr(0, 20) + json + glb.substr(20 + jsonLength);
  writeLe32(out, 8, uint32_t(out.size()));
  writeLe32(out, 12, uint32_t(json.size()));
  return out;
}

// Serialised in memory, then written complete or not at all (core/files.h).
void writeAtomically(const Writer& w, bool binary) {
  std::ostringstream bytes;
  tg::TinyGLTF gltf;
  if (!gltf.WriteGltfSceneToStream(&w.model, bytes, /*prettyPrint=*/!binary, binary))
    w.fail("cannot serialise the scene");
  writeFileAtomically(
      w.path, binary ? glbWithoutInfiniteZfar(bytes.str(), w) : withoutInfiniteZfar(bytes.str()));
}

}  // namespace

std::vector<std::string> writeGlb(const Scene& scene, const std::string& path) {
  const std::string ext = lowerExtension(path);
  if (ext != ".glb" && ext != ".gltf")
    throw InputError(path, "unsupported extension '" + ext + "', expected .glb or .gltf");
  Writer w{scene, path, {}};
  buildModel(w);
  writeAtomically(w, ext == ".glb");
  std::vector<std::string> warnings;
  if (scene.environment.type != Environment::Type::None)
    warnings.push_back(path + ": environment '" + scene.environment.name +
                       "' not written, glTF 2.0 has no environment lighting");
  return warnings;
}

}  // namespace photovr
