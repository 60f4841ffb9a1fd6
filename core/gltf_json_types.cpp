#include "core/gltf_json_types.h"

#include <cmath>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/error.h"

namespace photovr {
namespace {

using Json = nlohmann::json;

enum class Kind {
  Number,
  Integer,  // an integral number (glTF indices, enums, byte counts)
  String,
  Bool,
  Object,        // checked against 'schema'
  ObjectArray,   // each element an object checked against 'schema'
  NumberArray,   // of 'length' numbers (0: any length)
  IntegerArray,  // of integers, any length
  StringArray,
  IntegerMap,  // an object whose every member is an integer (a primitive's attributes)
};

struct Schema;

struct Member {
  std::string_view name;
  Kind kind;
  const Schema* schema = nullptr;
  size_t length = 0;
};

struct Schema {
  std::vector<Member> members;
};

Member number(std::string_view name) {
  return {name, Kind::Number};
}
Member integer(std::string_view name) {
  return {name, Kind::Integer};
}
Member string(std::string_view name) {
  return {name, Kind::String};
}
Member numbers(std::string_view name, size_t length) {
  return {name, Kind::NumberArray, nullptr, length};
}
Member object(std::string_view name, const Schema& schema) {
  return {name, Kind::Object, &schema};
}
Member objects(std::string_view name, const Schema& schema) {
  return {name, Kind::ObjectArray, &schema};
}

// glTF 2.0 §5 (the members the loader reads) and the extensions it supports.
const Schema kTextureTransform{
    {numbers("offset", 2), number("rotation"), numbers("scale", 2), integer("texCoord")}};
const Schema kTextureInfoExtensions{{object("KHR_texture_transform", kTextureTransform)}};
const Schema kTextureInfo{
    {integer("index"), integer("texCoord"), object("extensions", kTextureInfoExtensions)}};
const Schema kNormalTextureInfo{{integer("index"), integer("texCoord"), number("scale"),
                                 object("extensions", kTextureInfoExtensions)}};
const Schema kOcclusionTextureInfo{{integer("index"), integer("texCoord"), number("strength"),
                                    object("extensions", kTextureInfoExtensions)}};
const Schema kPbr{{numbers("baseColorFactor", 4), object("baseColorTexture", kTextureInfo),
                   number("metallicFactor"), number("roughnessFactor"),
                   object("metallicRoughnessTexture", kTextureInfo)}};
const Schema kEmissiveStrength{{number("emissiveStrength")}};
const Schema kIor{{number("ior")}};
const Schema kUnlit{};
const Schema kSheen{{numbers("sheenColorFactor", 3), number("sheenRoughnessFactor"),
                     object("sheenColorTexture", kTextureInfo),
                     object("sheenRoughnessTexture", kTextureInfo)}};
const Schema kClearcoat{{number("clearcoatFactor"), number("clearcoatRoughnessFactor"),
                         object("clearcoatTexture", kTextureInfo),
                         object("clearcoatRoughnessTexture", kTextureInfo),
                         object("clearcoatNormalTexture", kNormalTextureInfo)}};
const Schema kSpecular{{number("specularFactor"), numbers("specularColorFactor", 3),
                        object("specularTexture", kTextureInfo),
                        object("specularColorTexture", kTextureInfo)}};
const Schema kTransmission{
    {number("transmissionFactor"), object("transmissionTexture", kTextureInfo)}};
const Schema kVolume{{number("thicknessFactor"), object("thicknessTexture", kTextureInfo),
                      number("attenuationDistance"), numbers("attenuationColor", 3)}};
const Schema kMaterialExtensions{
    {object("KHR_materials_clearcoat", kClearcoat), object("KHR_materials_sheen", kSheen),
     object("KHR_materials_emissive_strength", kEmissiveStrength),
     object("KHR_materials_ior", kIor), object("KHR_materials_specular", kSpecular),
     object("KHR_materials_transmission", kTransmission), object("KHR_materials_unlit", kUnlit),
     object("KHR_materials_volume", kVolume)}};
const Schema kMaterial{{string("name"),
                        object("pbrMetallicRoughness", kPbr),
                        object("normalTexture", kNormalTextureInfo),
                        object("occlusionTexture", kOcclusionTextureInfo),
                        object("emissiveTexture", kTextureInfo),
                        numbers("emissiveFactor", 3),
                        string("alphaMode"),
                        number("alphaCutoff"),
                        {"doubleSided", Kind::Bool},
                        object("extensions", kMaterialExtensions)}};
const Schema kPrimitive{
    {{"attributes", Kind::IntegerMap}, integer("indices"), integer("material"), integer("mode")}};
const Schema kMesh{{string("name"), objects("primitives", kPrimitive), numbers("weights", 0)}};
const Schema kNodeLight{{integer("light")}};
const Schema kNodeExtensions{{object("KHR_lights_punctual", kNodeLight)}};
const Schema kNode{{string("name"),
                    integer("camera"),
                    {"children", Kind::IntegerArray},
                    numbers("matrix", 16),
                    integer("mesh"),
                    numbers("rotation", 4),
                    numbers("scale", 3),
                    numbers("translation", 3),
                    object("extensions", kNodeExtensions)}};
const Schema kScene{{string("name"), {"nodes", Kind::IntegerArray}}};
const Schema kAccessor{{string("name"),
                        integer("bufferView"),
                        integer("byteOffset"),
                        integer("componentType"),
                        {"normalized", Kind::Bool},
                        integer("count"),
                        string("type"),
                        numbers("max", 0),
                        numbers("min", 0)}};
const Schema kBufferView{{string("name"), integer("buffer"), integer("byteOffset"),
                          integer("byteLength"), integer("byteStride"), integer("target")}};
const Schema kBuffer{{string("name"), string("uri"), integer("byteLength")}};
const Schema kImage{{string("name"), string("uri"), string("mimeType"), integer("bufferView")}};
const Schema kSampler{{string("name"), integer("magFilter"), integer("minFilter"), integer("wrapS"),
                       integer("wrapT")}};
const Schema kTexture{{string("name"), integer("sampler"), integer("source")}};
const Schema kPerspective{{number("aspectRatio"), number("yfov"), number("zfar"), number("znear")}};
const Schema kOrthographic{{number("xmag"), number("ymag"), number("zfar"), number("znear")}};
const Schema kCamera{{string("name"), string("type"), object("perspective", kPerspective),
                      object("orthographic", kOrthographic)}};
const Schema kSpot{{number("innerConeAngle"), number("outerConeAngle")}};
const Schema kLight{{string("name"), string("type"), numbers("color", 3), number("intensity"),
                     number("range"), object("spot", kSpot)}};
const Schema kLights{{objects("lights", kLight)}};
const Schema kRootExtensions{{object("KHR_lights_punctual", kLights)}};
const Schema kRoot{{integer("scene"),
                    objects("scenes", kScene),
                    objects("nodes", kNode),
                    objects("meshes", kMesh),
                    objects("materials", kMaterial),
                    objects("textures", kTexture),
                    objects("images", kImage),
                    objects("samplers", kSampler),
                    objects("accessors", kAccessor),
                    objects("bufferViews", kBufferView),
                    objects("buffers", kBuffer),
                    objects("cameras", kCamera),
                    {"extensionsUsed", Kind::StringArray},
                    {"extensionsRequired", Kind::StringArray},
                    object("extensions", kRootExtensions)}};

bool isInteger(const Json& v) {
  if (v.is_number_integer()) return true;
  if (!v.is_number_float()) return false;
  const double d = v.get<double>();
  return std::isfinite(d) && d == std::trunc(d);
}

bool allOf(const Json& v, bool (*test)(const Json&)) {
  if (!v.is_array()) return false;
  for (const Json& e : v)
    if (!test(e)) return false;
  return true;
}

bool isNumber(const Json& v) {
  return v.is_number();
}
bool isString(const Json& v) {
  return v.is_string();
}

std::string expected(const Member& m) {
  switch (m.kind) {
    case Kind::Number:
      return "a number";
    case Kind::Integer:
      return "an integer";
    case Kind::String:
      return "a string";
    case Kind::Bool:
      return "true or false";
    case Kind::Object:
      return "an object";
    case Kind::ObjectArray:
      return "an array of objects";
    case Kind::NumberArray:
      return m.length ? "an array of " + std::to_string(m.length) + " numbers"
                      : "an array of numbers";
    case Kind::IntegerArray:
      return "an array of integers";
    case Kind::StringArray:
      return "an array of strings";
    case Kind::IntegerMap:
      return "an object of integers";
  }
  return "";
}

std::string described(const Json& v) {
  if (v.is_array()) {
    std::string kinds = "numbers";
    for (const Json& e : v)
      if (!e.is_number()) kinds = "values";
    return "an array of " + std::to_string(v.size()) + " " + kinds;
  }
  if (v.is_number()) return "the number " + v.dump();
  if (v.is_string()) return "a string";
  if (v.is_boolean()) return v.get<bool>() ? "true" : "false";
  if (v.is_object()) return "an object";
  return "null";
}

bool hasKind(const Json& v, const Member& m) {
  switch (m.kind) {
    case Kind::Number:
      return v.is_number();
    case Kind::Integer:
      return isInteger(v);
    case Kind::String:
      return v.is_string();
    case Kind::Bool:
      return v.is_boolean();
    case Kind::Object:
      return v.is_object();
    case Kind::ObjectArray:
      return allOf(v, [](const Json& e) { return e.is_object(); });
    case Kind::NumberArray:
      return allOf(v, isNumber) && (!m.length || v.size() == m.length);
    case Kind::IntegerArray:
      return allOf(v, isInteger);
    case Kind::StringArray:
      return allOf(v, isString);
    case Kind::IntegerMap:
      if (!v.is_object()) return false;
      for (const auto& item : v.items())
        if (!isInteger(item.value())) return false;
      return true;
  }
  return false;
}

void checkObject(const Json& object, const Schema& schema, const std::string& where,
                 const std::string& path) {
  for (const Member& m : schema.members) {
    const auto it = object.find(m.name);
    if (it == object.end()) continue;
    const std::string name = (where.empty() ? "" : where + ".") + std::string(m.name);
    if (!hasKind(*it, m))
      throw InputError(path, name + ": expected " + expected(m) + ", got " + described(*it));
    if (m.kind == Kind::Object) checkObject(*it, *m.schema, name, path);
    if (m.kind == Kind::ObjectArray)
      for (size_t i = 0; i < it->size(); ++i)
        checkObject((*it)[i], *m.schema, name + "[" + std::to_string(i) + "]", path);
  }
}

}  // namespace

void checkGltfJsonTypes(const uint8_t* json, size_t size, const std::string& path) {
  // No exceptions from the parser: a syntax error is reported by tinygltf's parse.
  const Json root = Json::parse(json, json + size, nullptr, false);
  if (root.is_discarded()) return;
  if (!root.is_object())
    throw InputError(path, "the glTF JSON is " + described(root) + ", not an object");
  checkObject(root, kRoot, "", path);
}

std::vector<std::string> requiredExtensions(const uint8_t* json, size_t size) {
  const Json root = Json::parse(json, json + size, nullptr, false);
  std::vector<std::string> names;
  if (root.is_discarded() || !root.is_object()) return names;
  const auto it = root.find("extensionsRequired");
  if (it == root.end() || !it->is_array()) return names;
  for (const Json& name : *it)
    if (name.is_string()) names.push_back(name.get<std::string>());
  return names;
}

}  // namespace photovr
