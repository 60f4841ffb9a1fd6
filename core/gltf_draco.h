// KHR_draco_mesh_compression through Debian's libdraco: a primitive's geometry decoded
// from its Draco bitstream (the extension's bufferView), its attributes found by the
// Draco unique ids the extension names. The primitive's accessors only describe the
// decoded data; they have no bufferView of their own.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace photovr {

struct DracoGeometry {
  std::vector<glm::vec3> positions, normals;
  std::vector<glm::vec4> tangents;
  std::vector<glm::vec2> uv0, uv1;
  std::vector<uint32_t> indices;  // a triangle list
};

// Decodes a Draco mesh; 'attributes' maps glTF attribute names (POSITION, NORMAL,
// TANGENT, TEXCOORD_0, TEXCOORD_1) to Draco unique ids, others are ignored. Returns false
// with 'problem' set (one line) for a bitstream that does not decode, is a point cloud,
// or lacks a named attribute or has it with too few components.
bool decodeDraco(const uint8_t* bytes, size_t size, const std::map<std::string, int>& attributes,
                 DracoGeometry& out, std::string& problem);

// tinygltf refuses a primitive whose indices accessor has no bufferView, which is how
// Draco files are written. Returns the glTF JSON with each such accessor pointed at its
// primitive's Draco bufferView (the loader decodes the primitive and never reads the
// accessor), or empty when nothing needed it. 'json' must parse (checked before).
std::string withDracoIndexViews(const uint8_t* json, size_t size);

}  // namespace photovr
