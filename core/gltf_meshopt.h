// EXT_meshopt_compression through Debian's libmeshoptimizer: buffer views whose bytes are
// stored compressed in another buffer, decoded into the view's own (fallback) buffer before
// anything reads an accessor, so the rest of the loader sees an uncompressed file.
//
// The extension (KhronosGroup glTF extension registry, EXT_meshopt_compression) puts on a
// bufferView: the source buffer, byteOffset, byteLength of the compressed bytes, byteStride
// and count of the decoded elements, a mode (ATTRIBUTES, TRIANGLES, INDICES) and a filter
// (NONE, OCTAHEDRAL, QUATERNION, EXPONENTIAL) applied after decoding. The view's own buffer
// is usually a fallback marked { "fallback": true } with no data at all.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace tinygltf {
class Model;
}

namespace photovr {

// The glTF JSON with every fallback buffer's data replaced by a 4-byte placeholder that
// tinygltf accepts (it refuses a buffer without data, or reads a GLB's BIN chunk into it),
// and the declared size of each such buffer. 'json' empty when nothing needed it.
struct MeshoptFallbacks {
  std::string json;
  std::vector<std::pair<int, size_t>> declaredSizes;  // buffer index, byteLength
};
MeshoptFallbacks withMeshoptFallbacks(const uint8_t* json, size_t size);

// Decodes every compressed buffer view of 'model' into its buffer (the fallbacks sized
// first to hold their views, at most their declared size). Throws InputError naming 'path'
// and the view for a range, stride, count, mode or filter the extension does not allow, or
// bytes that do not decode.
void decodeMeshoptViews(tinygltf::Model& model, const MeshoptFallbacks& fallbacks,
                        const std::string& path);

}  // namespace photovr
