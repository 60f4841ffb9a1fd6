// The JSON side of EXT_meshopt_compression (core/gltf_meshopt.h), before tinygltf parses
// the file; gltf_meshopt.cpp is the side after, on tinygltf's model.
#include <string_view>

#include <nlohmann/json.hpp>

#include "core/gltf_meshopt.h"

namespace photovr {
namespace {

using Json = nlohmann::json;

constexpr const char* kExtension = "EXT_meshopt_compression";
// Four zero bytes as a data URI: the smallest buffer tinygltf accepts in place of a fallback.
constexpr const char* kPlaceholderUri = "data:application/octet-stream;base64,AAAAAA==";

bool isFallback(const Json& buffer) {
  if (!buffer.is_object() || !buffer.contains("extensions")) return false;
  const Json& ext = buffer["extensions"];
  if (!ext.is_object() || !ext.contains(kExtension) || !ext[kExtension].is_object()) return false;
  const Json& meshopt = ext[kExtension];
  return meshopt.contains("fallback") && meshopt["fallback"].is_boolean() &&
         meshopt["fallback"].get<bool>();
}

}  // namespace

MeshoptFallbacks withMeshoptFallbacks(const uint8_t* json, size_t size) {
  MeshoptFallbacks out;
  const std::string_view text(reinterpret_cast<const char*>(json), size);
  if (text.find(kExtension) == std::string_view::npos) return out;  // the common case
  Json root = Json::parse(json, json + size, nullptr, false);
  if (root.is_discarded() || !root.is_object() || !root.contains("buffers") ||
      !root["buffers"].is_array())
    return out;
  Json& buffers = root["buffers"];
  for (size_t i = 0; i < buffers.size(); ++i) {
    Json& buffer = buffers[i];
    if (!isFallback(buffer) || !buffer.contains("byteLength") ||
        !buffer["byteLength"].is_number_unsigned())
      continue;
    out.declaredSizes.emplace_back(int(i), buffer["byteLength"].get<size_t>());
    buffer["uri"] = kPlaceholderUri;
    buffer["byteLength"] = 4;
  }
  if (!out.declaredSizes.empty()) out.json = root.dump();
  return out;
}

}  // namespace photovr
