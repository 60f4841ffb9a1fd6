#include "core/gltf_meshopt.h"

#include <meshoptimizer.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <map>

#include "core/error.h"

namespace photovr {
namespace {

namespace tg = tinygltf;

constexpr const char* kExtension = "EXT_meshopt_compression";
// A decoded view larger than this is refused: the counts come from the file, and a hostile
// one would otherwise make the loader allocate what the machine does not have.
constexpr size_t kMaxDecodedBytes = size_t(1) << 31;

// The extension's object on a buffer view, with the fields the decoder needs.
struct CompressedView {
  int buffer = -1;
  size_t byteOffset = 0, byteLength = 0, byteStride = 0, count = 0;
  std::string mode, filter = "NONE";
};

// A non-negative integer member, or 'fallback' when it is absent; -1 when it is present but
// not a non-negative integer.
long long member(const tg::Value& object, const char* name, long long fallback) {
  if (!object.Has(name)) return fallback;
  const tg::Value& v = object.Get(name);
  if (!v.IsNumber()) return -1;
  const double d = v.GetNumberAsDouble();
  return d >= 0.0 && d <= 9.0e15 && d == double(static_cast<long long>(d))
             ? static_cast<long long>(d)
             : -1;
}

std::string stringMember(const tg::Value& object, const char* name, const std::string& fallback) {
  if (!object.Has(name)) return fallback;
  const tg::Value& v = object.Get(name);
  return v.IsString() ? v.Get<std::string>() : std::string("(not a string)");
}

CompressedView readView(const tg::Value& ext, const std::string& where, const std::string& path) {
  if (!ext.IsObject()) throw InputError(path, where + ": " + kExtension + " is not an object");
  const long long buffer = member(ext, "buffer", -1), offset = member(ext, "byteOffset", 0),
                  length = member(ext, "byteLength", -1), stride = member(ext, "byteStride", -1),
                  count = member(ext, "count", -1);
  if (buffer < 0 || offset < 0 || length < 0 || stride < 0 || count < 0)
    throw InputError(path, where + ": " + kExtension +
                               " needs non-negative integer buffer, byteLength, byteStride "
                               "and count");
  CompressedView v;
  v.buffer = int(std::min<long long>(buffer, 1 << 30));
  v.byteOffset = size_t(offset);
  v.byteLength = size_t(length);
  v.byteStride = size_t(stride);
  v.count = size_t(count);
  v.mode = stringMember(ext, "mode", "(missing)");
  v.filter = stringMember(ext, "filter", "NONE");
  return v;
}

// The extension's rules on stride, count and filter for each mode.
std::string strideProblem(const CompressedView& v) {
  if (v.mode == "ATTRIBUTES") {
    if (v.byteStride == 0 || v.byteStride % 4 != 0 || v.byteStride > 256)
      return "ATTRIBUTES byteStride " + std::to_string(v.byteStride) +
             " is not a multiple of 4 in [4, 256]";
    if (v.filter == "NONE" || v.filter == "EXPONENTIAL") return "";
    if (v.filter == "OCTAHEDRAL" && (v.byteStride == 4 || v.byteStride == 8)) return "";
    if (v.filter == "QUATERNION" && v.byteStride == 8) return "";
    return "filter " + v.filter + " with byteStride " + std::to_string(v.byteStride) +
           " is not allowed";
  }
  if (v.mode != "TRIANGLES" && v.mode != "INDICES")
    return "mode " + v.mode + " is not ATTRIBUTES, TRIANGLES or INDICES";
  if (v.byteStride != 2 && v.byteStride != 4)
    return v.mode + " byteStride " + std::to_string(v.byteStride) + " is not 2 or 4";
  if (v.mode == "TRIANGLES" && v.count % 3 != 0)
    return "TRIANGLES count " + std::to_string(v.count) + " is not a multiple of 3";
  if (v.filter != "NONE") return "filter " + v.filter + " on " + v.mode + " is not allowed";
  return "";
}

// meshoptimizer's decoder for the mode, then the filter in place; its own checks of the
// stream (header, lengths) give a non-zero result for bytes that do not decode.
int decode(const CompressedView& v, uint8_t* out, const uint8_t* in) {
  int result = 0;
  if (v.mode == "ATTRIBUTES")
    result = meshopt_decodeVertexBuffer(out, v.count, v.byteStride, in, v.byteLength);
  else if (v.mode == "TRIANGLES")
    result = meshopt_decodeIndexBuffer(out, v.count, v.byteStride, in, v.byteLength);
  else
    result = meshopt_decodeIndexSequence(out, v.count, v.byteStride, in, v.byteLength);
  if (result != 0) return result;
  if (v.filter == "OCTAHEDRAL") meshopt_decodeFilterOct(out, v.count, v.byteStride);
  if (v.filter == "QUATERNION") meshopt_decodeFilterQuat(out, v.count, v.byteStride);
  if (v.filter == "EXPONENTIAL") meshopt_decodeFilterExp(out, v.count, v.byteStride);
  return 0;
}

void decodeView(tg::Model& model, const tg::BufferView& view, const CompressedView& v,
                const std::string& where, const std::string& path) {
  if (const std::string problem = strideProblem(v); !problem.empty())
    throw InputError(path, where + ": " + kExtension + " " + problem);
  if (v.buffer < 0 || size_t(v.buffer) >= model.buffers.size())
    throw InputError(
        path, where + ": " + kExtension + " buffer " + std::to_string(v.buffer) + " out of range");
  const std::vector<uint8_t>& source = model.buffers[size_t(v.buffer)].data;
  if (v.byteOffset > source.size() || v.byteLength > source.size() - v.byteOffset)
    throw InputError(path, where + ": " + kExtension + " bytes " + std::to_string(v.byteOffset) +
                               "+" + std::to_string(v.byteLength) + " out of range of buffer " +
                               std::to_string(v.buffer));
  const size_t decoded = v.count * v.byteStride;  // stride <= 256, count bounded below
  if (v.count > kMaxDecodedBytes || decoded > view.byteLength)
    throw InputError(path, where + ": " + kExtension + " decodes " + std::to_string(v.count) +
                               " x " + std::to_string(v.byteStride) +
                               " bytes, more than the view's byteLength " +
                               std::to_string(view.byteLength));
  std::vector<uint8_t>& target = model.buffers[size_t(view.buffer)].data;
  if (view.byteOffset > target.size() || decoded > target.size() - view.byteOffset)
    throw InputError(path, where + ": out of range of its buffer " + std::to_string(view.buffer));
  // Decoded into a copy: the source may be the view's own buffer.
  std::vector<uint8_t> out(decoded);
  const std::vector<uint8_t> in(source.begin() + std::ptrdiff_t(v.byteOffset),
                                source.begin() + std::ptrdiff_t(v.byteOffset + v.byteLength));
  if (decode(v, out.data(), in.data()) != 0)
    throw InputError(path, where + ": " + kExtension + " " + v.mode + " data does not decode");
  std::copy(out.begin(), out.end(), target.begin() + std::ptrdiff_t(view.byteOffset));
}

// Each fallback buffer sized to hold the views that point into it: the end of the furthest
// one, and never more than it declared (checkBufferViews then reports views beyond it).
void sizeFallbacks(tg::Model& model, const MeshoptFallbacks& fallbacks) {
  std::map<int, size_t> needed;
  for (const tg::BufferView& view : model.bufferViews)
    if (view.byteOffset <= kMaxDecodedBytes && view.byteLength <= kMaxDecodedBytes)
      needed[view.buffer] = std::max(needed[view.buffer], view.byteOffset + view.byteLength);
  for (const auto& [buffer, declared] : fallbacks.declaredSizes)
    if (buffer >= 0 && size_t(buffer) < model.buffers.size())
      model.buffers[size_t(buffer)].data.assign(std::min(declared, needed[buffer]), 0);
}

}  // namespace

void decodeMeshoptViews(tg::Model& model, const MeshoptFallbacks& fallbacks,
                        const std::string& path) {
  sizeFallbacks(model, fallbacks);
  for (size_t i = 0; i < model.bufferViews.size(); ++i) {
    const tg::BufferView& view = model.bufferViews[i];
    const auto ext = view.extensions.find(kExtension);
    if (ext == view.extensions.end()) continue;
    const std::string where = "bufferView " + std::to_string(i);
    if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size())
      throw InputError(path,
                       where + ": buffer index " + std::to_string(view.buffer) + " out of range");
    decodeView(model, view, readView(ext->second, where, path), where, path);
  }
}

}  // namespace photovr
