#include "core/gltf_draco.h"

#include <memory>

#include <draco/compression/decode.h>
#include <nlohmann/json.hpp>

namespace photovr {
namespace {

using Json = nlohmann::json;

// One attribute's values per Draco point, as N floats (Draco dequantises on decoding;
// normalised integer attributes are converted by ConvertValue).
template <int N>
bool readAttribute(const draco::Mesh& mesh, int uniqueId, const std::string& name,
                   std::vector<glm::vec<N, float>>& out, std::string& problem) {
  const draco::PointAttribute* a = mesh.GetAttributeByUniqueId(uint32_t(uniqueId));
  if (!a) {
    problem = name + ": no Draco attribute with unique id " + std::to_string(uniqueId);
    return false;
  }
  if (a->num_components() < N) {
    problem = name + ": Draco attribute has " + std::to_string(a->num_components()) +
              " components, expected " + std::to_string(N);
    return false;
  }
  out.resize(mesh.num_points());
  for (draco::PointIndex p(0); p < mesh.num_points(); ++p)
    if (!a->ConvertValue<float>(a->mapped_index(p), int8_t(N), &out[p.value()][0])) {
      problem = name + ": Draco attribute values do not convert to float";
      return false;
    }
  return true;
}

}  // namespace

bool decodeDraco(const uint8_t* bytes, size_t size, const std::map<std::string, int>& attributes,
                 DracoGeometry& out, std::string& problem) {
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(bytes), size);
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
  if (!decoded.ok()) {
    problem = "Draco bitstream does not decode as a mesh: " + decoded.status().error_msg_string();
    return false;
  }
  const std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
  bool ok = true;
  for (const auto& [name, id] : attributes) {
    if (name == "POSITION") ok = ok && readAttribute<3>(*mesh, id, name, out.positions, problem);
    if (name == "NORMAL") ok = ok && readAttribute<3>(*mesh, id, name, out.normals, problem);
    if (name == "TANGENT") ok = ok && readAttribute<4>(*mesh, id, name, out.tangents, problem);
    if (name == "TEXCOORD_0") ok = ok && readAttribute<2>(*mesh, id, name, out.uv0, problem);
    if (name == "TEXCOORD_1") ok = ok && readAttribute<2>(*mesh, id, name, out.uv1, problem);
  }
  if (!ok) return false;
  out.indices.clear();
  out.indices.reserve(size_t(mesh->num_faces()) * 3);
  for (draco::FaceIndex f(0); f < mesh->num_faces(); ++f)
    for (int k = 0; k < 3; ++k) out.indices.push_back(mesh->face(f)[k].value());
  return true;
}

std::string withDracoIndexViews(const uint8_t* json, size_t size) {
  Json root = Json::parse(json, json + size, nullptr, false);
  if (root.is_discarded() || !root.is_object() || !root.contains("meshes") ||
      !root.contains("accessors") || !root["meshes"].is_array() || !root["accessors"].is_array())
    return "";
  Json& accessors = root["accessors"];
  bool changed = false;
  for (Json& mesh : root["meshes"]) {
    if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array())
      continue;
    for (Json& prim : mesh["primitives"]) {
      const Json* ext = nullptr;
      if (prim.is_object() && prim.contains("extensions") && prim["extensions"].is_object() &&
          prim["extensions"].contains("KHR_draco_mesh_compression"))
        ext = &prim["extensions"]["KHR_draco_mesh_compression"];
      if (!ext || !ext->is_object() || !ext->contains("bufferView") ||
          !(*ext)["bufferView"].is_number_integer() || !prim.contains("indices") ||
          !prim["indices"].is_number_integer())
        continue;
      const long index = prim["indices"].get<long>();
      if (index < 0 || size_t(index) >= accessors.size() || !accessors[size_t(index)].is_object())
        continue;
      Json& accessor = accessors[size_t(index)];
      if (accessor.contains("bufferView")) continue;
      accessor["bufferView"] = (*ext)["bufferView"];
      changed = true;
    }
  }
  return changed ? root.dump() : "";
}

}  // namespace photovr
