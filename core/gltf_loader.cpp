#include "core/gltf_loader.h"

#include <tiny_gltf.h>

#include <stb_image.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string_view>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "core/error.h"
#include "core/files.h"
#include "core/gltf_draco.h"
#include "core/gltf_meshopt.h"
#include "core/gltf_json_types.h"
#include "core/image_io.h"
#include "core/scene_transform.h"
#include "core/mesh_util.h"

namespace photovr {
namespace {

namespace fs = std::filesystem;
namespace tg = tinygltf;

// An accessor without a bufferView is all zeros (glTF 2.0 §3.6.2.1); its count is not
// bounded by any buffer, so cap it to keep a malicious count from exhausting memory.
constexpr size_t kMaxZeroAccessorCount = size_t(1) << 26;
constexpr int kTextureNotLoaded = -2;

const std::vector<std::string> kSupportedExtensions = {
    "KHR_draco_mesh_compression", "KHR_lights_punctual",
    "KHR_materials_clearcoat",    "KHR_materials_emissive_strength",
    "KHR_materials_ior",          "KHR_materials_sheen",
    "KHR_materials_specular",     "KHR_materials_transmission",
    "KHR_materials_unlit",        "KHR_materials_volume",
    "KHR_texture_transform",      "EXT_meshopt_compression"};

bool supported(const std::string& extension) {
  return std::find(kSupportedExtensions.begin(), kSupportedExtensions.end(), extension) !=
         kSupportedExtensions.end();
}

// ---------------------------------------------------------------------------------------
// Reading and parsing the file

std::string firstLine(const std::string& text) {
  const size_t begin = text.find_first_not_of(" \t\r\n");
  if (begin == std::string::npos) return "";
  const size_t end = text.find_first_of("\r\n", begin);
  return text.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
}

std::vector<uint8_t> readFile(const std::string& path) {
  // tinygltf takes 32-bit sizes, and .glb cannot describe more (glTF 2.0 §4.4.2).
  const std::string bytes =
      readRegularFile(path, "glTF file", std::numeric_limits<uint32_t>::max());
  if (bytes.empty()) throw InputError(path, "file is empty");
  return {bytes.begin(), bytes.end()};
}

bool isGlb(const std::vector<uint8_t>& bytes) {
  return bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
}

uint32_t readU32(const std::vector<uint8_t>& bytes, size_t at) {
  uint32_t v;  // .glb is little-endian (§4.4.1), as are the hosts photovr runs on
  std::memcpy(&v, &bytes[at], 4);
  return v;
}

// Walks the .glb chunk headers (glTF 2.0 §4.4) so that a truncated or lying file is refused
// here with a clear message; tinygltf 2.7's own chunk check is off by the 8-byte header.
void checkGlbLayout(const std::vector<uint8_t>& bytes, const std::string& path) {
  if (bytes.size() < 20)
    throw InputError(path, "truncated .glb: " + std::to_string(bytes.size()) +
                               " bytes, shorter than the 20-byte header");
  if (readU32(bytes, 4) != 2)
    throw InputError(path, "unsupported .glb container version " +
                               std::to_string(readU32(bytes, 4)) + " (expected 2)");
  const uint64_t length = readU32(bytes, 8);
  if (length > bytes.size())
    throw InputError(path, "truncated .glb: header declares " + std::to_string(length) +
                               " bytes, the file has " + std::to_string(bytes.size()));
  for (uint64_t at = 12; at < length;) {
    if (length - at < 8) throw InputError(path, "truncated .glb: chunk header cut off");
    const uint64_t chunkLength = readU32(bytes, size_t(at));
    if (chunkLength > length - at - 8)
      throw InputError(path, "truncated .glb: a chunk declares " + std::to_string(chunkLength) +
                                 " bytes, only " + std::to_string(length - at - 8) + " remain");
    at += 8 + chunkLength;
  }
}

// Keeps the encoded bytes of data-URI and external images for photovr's own decoder. Images
// in a bufferView are sliced later, after the view is range-checked: tinygltf passes an
// unchecked pointer for those, so it must not be read here.
bool keepEncodedImage(tg::Image* image, const int, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void*) {
  if (image->bufferView < 0 && bytes && size > 0) image->image.assign(bytes, bytes + size);
  image->as_is = true;
  return true;
}

// tinygltf quotes whole data URIs in its messages; a megabyte of base64 helps no one.
std::string elideDataUris(std::string line) {
  for (size_t at = line.find("data:"); at != std::string::npos; at = line.find("data:", at)) {
    const size_t end = line.find_first_of(" '\"", at);
    line.replace(at, (end == std::string::npos ? line.size() : end) - at, "<data URI>");
  }
  return line;
}

std::string describeParseFailure(const std::string& err, const std::string& warn) {
  const std::string line = elideDataUris(firstLine(err.empty() ? warn : err));
  if (line.empty()) return "tinygltf could not parse the file";
  if (line.rfind("[json.exception", 0) == 0) return "invalid JSON: " + line;
  // Name the object behind tinygltf's two terse buffer messages.
  if (line.rfind("Failed to decode 'uri'", 0) == 0 && line.find("Buffer") != std::string::npos)
    return "buffer data URI is not valid base64 or is shorter than its byteLength";
  if (line.rfind("File read error : ", 0) == 0)
    return "cannot read " + line.substr(std::strlen("File read error : "));
  if (line.rfind("File not found : ", 0) == 0)
    return "buffer file not found: " + line.substr(std::strlen("File not found : "));
  return line;
}

// tinygltf's warnings about images are dropped: loadTexture reports those itself, with the
// consequence (factor fallback) spelled out.
void forwardWarnings(const std::string& path, const std::string& warn,
                     std::vector<std::string>& out) {
  size_t start = 0;
  while (start < warn.size()) {
    size_t end = warn.find('\n', start);
    if (end == std::string::npos) end = warn.size();
    const std::string line = firstLine(warn.substr(start, end - start));
    const bool aboutImage =
        line.find("image") != std::string::npos || line.find("File not found") != std::string::npos;
    if (!line.empty() && !aboutImage) out.push_back(path + ": " + line);
    start = end + 1;
  }
}

// JSON nests at most this deep here: tinygltf's parser recurses once per level and a file
// nested ~20 000 deep overflowed the stack (a crash, not an error). glTF itself nests
// fewer than 10 levels; 'extras' may add some.
constexpr int kMaxJsonDepth = 512;

void checkJsonDepth(const uint8_t* json, size_t size, const std::string& path) {
  int depth = 0;
  bool inString = false;
  for (size_t i = 0; i < size; ++i) {
    const char c = char(json[i]);
    if (inString) {
      if (c == '\\')
        ++i;  // skip the escaped character
      else if (c == '"')
        inString = false;
    } else if (c == '"') {
      inString = true;
    } else if (c == '{' || c == '[') {
      if (++depth > kMaxJsonDepth)
        throw InputError(path,
                         "JSON nested more than " + std::to_string(kMaxJsonDepth) + " levels deep");
    } else if (c == '}' || c == ']') {
      --depth;
    }
  }
}

// External buffers and images are read only from regular files (a directory, a FIFO or a
// device would make tinygltf allocate, block or read forever), and never expanded as shell
// words (tinygltf's default ExpandFilePath runs wordexp).
bool readRegularFile(std::vector<unsigned char>* out, std::string* err, const std::string& file,
                     void*) {
  std::error_code ec;
  if (!fs::exists(file, ec)) {
    if (err) *err += "File not found : " + file + "\n";
    return false;
  }
  const auto size = fs::is_regular_file(file, ec) ? fs::file_size(file, ec) : 0;
  if (!fs::is_regular_file(file, ec) || ec || size > std::numeric_limits<uint32_t>::max()) {
    if (err) *err += "not a regular file (a directory, FIFO or device), or over 4 GiB\n";
    return false;
  }
  std::ifstream in(file, std::ios::binary);
  out->assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  if (in.bad() || out->size() != size) {
    if (err) *err += "read error\n";
    return false;
  }
  return true;
}

bool regularFileExists(const std::string& file, void*) {
  std::error_code ec;
  return fs::exists(file, ec);
}

std::string pathAsIs(const std::string& file, void*) {
  return file;
}

std::string baseDirOf(const std::string& path) {
  const fs::path parent = fs::path(path).parent_path();
  return parent.empty() ? "." : parent.string();
}

// Why a required extension is not supported, where there is more to say than its name.
std::string whyUnsupported(const std::string& name) {
  if (name == "KHR_texture_basisu")
    return " (Basis Universal textures: Debian 12 ships no Basis decoder)";
  return "";
}

// glTF 2.0 §3.12: a loader must refuse a file that requires an extension it lacks; checked
// on the JSON before anything else, so it is the first and only error.
void checkRequiredExtensions(const uint8_t* json, size_t size, const std::string& path) {
  std::string list;
  for (const std::string& name : requiredExtensions(json, size))
    if (!supported(name)) list += (list.empty() ? "" : ", ") + name + whyUnsupported(name);
  if (!list.empty()) throw InputError(path, "requires unsupported extension(s) " + list);
}

// The JSON's own checks, before tinygltf sees it.
void checkJson(const uint8_t* json, size_t size, const std::string& path) {
  checkJsonDepth(json, size, path);
  checkRequiredExtensions(json, size, path);
  checkGltfJsonTypes(json, size, path);
}

// The JSON with Draco primitives' index accessors pointed at a buffer view
// (withDracoIndexViews), or empty when the file has none (the common case skips parsing).
std::string withDracoViews(const uint8_t* json, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(json), size);
  if (text.find("KHR_draco_mesh_compression") == std::string_view::npos) return "";
  return withDracoIndexViews(json, size);
}

// A GLB with its JSON chunk replaced by 'json' (padded with spaces to 4 bytes, glTF 2.0
// §4.4.3.1), the rest as it was; 'glb' itself when 'json' is empty.
std::vector<uint8_t> withJsonChunk(const std::vector<uint8_t>& glb, std::string json) {
  if (json.empty()) return glb;
  while (json.size() % 4 != 0) json.push_back(' ');
  const size_t oldChunk = 8 + size_t(readU32(glb, 12));
  std::vector<uint8_t> out(glb.begin(), glb.begin() + 12);
  auto putU32 = [&](uint32_t v) {
    for (int k = 0; k < 4; ++k) out.push_back(uint8_t(v >> (8 * k)));
  };
  putU32(uint32_t(json.size()));
  putU32(0x4E4F534Au);  // "JSON"
  out.insert(out.end(), json.begin(), json.end());
  out.insert(out.end(), glb.begin() + std::ptrdiff_t(std::min(12 + oldChunk, glb.size())),
             glb.end());
  const uint32_t total = uint32_t(out.size());
  for (int k = 0; k < 4; ++k) out[8 + size_t(k)] = uint8_t(total >> (8 * k));
  return out;
}

// The JSON as tinygltf is given it: Draco primitives' index accessors pointed at a buffer
// view, meshopt fallback buffers given placeholder data (their sizes kept in 'meshopt');
// empty when neither was needed.
std::string preparedJson(const uint8_t* json, size_t size, MeshoptFallbacks& meshopt) {
  std::string text = withDracoViews(json, size);
  if (!text.empty()) {
    json = reinterpret_cast<const uint8_t*>(text.data());
    size = text.size();
  }
  meshopt = withMeshoptFallbacks(json, size);
  if (!meshopt.json.empty()) text = std::move(meshopt.json);
  return text;
}

// tinygltf's result, with an exception it lets out turned into the one-line error: a GLB
// buffer with byteLength 0 makes it index an empty vector with at() (found by fuzzing the
// meshopt decoder's inputs, issue 23).
template <typename Load>
bool tinygltfLoads(const std::string& path, Load load) {
  try {
    return load();
  } catch (const std::exception& e) {
    throw InputError(path, std::string("tinygltf could not parse the file (") + e.what() + ")");
  }
}

tg::Model parseModel(const std::string& path, const std::vector<uint8_t>& bytes,
                     std::vector<std::string>& warnings) {
  tg::TinyGLTF loader;
  loader.SetImageLoader(keepEncodedImage, nullptr);
  loader.SetFsCallbacks({regularFileExists, pathAsIs, readRegularFile, nullptr, nullptr});
  tg::Model model;
  std::string err, warn;
  const std::string baseDir = baseDirOf(path);
  MeshoptFallbacks meshopt;
  bool ok;
  if (isGlb(bytes)) {
    checkGlbLayout(bytes, path);
    const size_t jsonSize = std::min<size_t>(readU32(bytes, 12), bytes.size() - 20);
    checkJson(bytes.data() + 20, jsonSize, path);
    const std::vector<uint8_t> glb =
        withJsonChunk(bytes, preparedJson(bytes.data() + 20, jsonSize, meshopt));
    ok = tinygltfLoads(path, [&] {
      return loader.LoadBinaryFromMemory(&model, &err, &warn, glb.data(), unsigned(glb.size()),
                                         baseDir);
    });
  } else {
    checkJson(bytes.data(), bytes.size(), path);
    std::string text = preparedJson(bytes.data(), bytes.size(), meshopt);
    if (text.empty()) text.assign(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    ok = tinygltfLoads(path, [&] {
      return loader.LoadASCIIFromString(&model, &err, &warn, text.data(), unsigned(text.size()),
                                        baseDir);
    });
  }
  if (!ok) throw InputError(path, describeParseFailure(err, warn));
  forwardWarnings(path, warn, warnings);
  decodeMeshoptViews(model, meshopt, path);
  return model;
}

std::string unsupportedIn(const std::vector<std::string>& names) {
  std::string list;
  for (const std::string& name : names)
    if (!supported(name)) list += (list.empty() ? "" : ", ") + name;
  return list;
}

// Lists what the file uses (required ones were checked on the JSON: checkJson).
void checkExtensions(const tg::Model& model, const std::string& path,
                     std::vector<std::string>& warnings, std::vector<Scene::Extension>& used) {
  for (const std::string& name : model.extensionsUsed) used.push_back({name, supported(name)});
  if (const std::string used = unsupportedIn(model.extensionsUsed); !used.empty())
    warnings.push_back(path + ": ignores unsupported extension(s) " + used);
}

void checkBufferViews(const tg::Model& model, const std::string& path) {
  for (size_t i = 0; i < model.bufferViews.size(); ++i) {
    const tg::BufferView& view = model.bufferViews[i];
    const std::string where = "bufferView " + std::to_string(i);
    if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size())
      throw InputError(path,
                       where + ": buffer index " + std::to_string(view.buffer) + " out of range");
    const size_t size = model.buffers[size_t(view.buffer)].data.size();
    if (view.byteOffset > size || view.byteLength > size - view.byteOffset)
      throw InputError(path, where + ": bytes " + std::to_string(view.byteOffset) + "+" +
                                 std::to_string(view.byteLength) + " out of range of buffer " +
                                 std::to_string(view.buffer) + " (" + std::to_string(size) +
                                 " bytes)");
    // glTF 2.0 §5.11.4: byteStride is a multiple of 4 in [4, 252].
    if (view.byteStride != 0 &&
        (view.byteStride < 4 || view.byteStride > 252 || view.byteStride % 4 != 0))
      throw InputError(path, where + ": invalid byteStride " + std::to_string(view.byteStride));
  }
}

// ---------------------------------------------------------------------------------------
// Conversion state

struct Loader {
  Loader(const std::string& p, const tg::Model& m)
      : path(p),
        baseDir(baseDirOf(p)),
        model(m),
        meshes(m.meshes.size()),
        meshConverted(m.meshes.size(), false),
        textures(m.textures.size(), kTextureNotLoaded),
        visited(m.nodes.size(), false),
        sceneNodeOf(m.nodes.size(), -1) {}

  [[noreturn]] void fail(const std::string& problem) const { throw InputError(path, problem); }
  void warn(const std::string& problem) { scene.warnings.push_back(path + ": " + problem); }

  std::string path;
  std::string baseDir;
  const tg::Model& model;
  Scene scene;
  std::vector<std::vector<int>> meshes;  // glTF mesh -> photovr meshes (one per primitive)
  std::vector<bool> meshConverted;
  std::vector<int> textures;     // glTF texture -> photovr texture, -1 unusable
  std::vector<bool> visited;     // nodes already placed, to catch cycles and shared children
  DoublePlacement placed;        // the scene's parts as placed in double, for storePlacement
  std::vector<int> sceneNodeOf;  // glTF node -> Scene::nodes, -1 when not in the scene
  int defaultMaterial = -1;
  struct SkinnedInstance {
    int instance, skin;  // Scene instance, glTF skin
  };
  std::vector<SkinnedInstance> skinnedInstances;  // bound by bindSkins once nodes are placed
};

template <typename T>
bool inRange(int index, const std::vector<T>& v) {
  return index >= 0 && size_t(index) < v.size();
}

std::string named(const std::string& name) {
  return "'" + name + "'";
}

// ---------------------------------------------------------------------------------------
// Accessors (glTF 2.0 §3.6)

struct AccessorView {
  const uint8_t* data = nullptr;  // null: no bufferView, every element is zero
  size_t count = 0;
  size_t stride = 0;
  int componentType = 0;
  int components = 0;
  bool normalized = false;
};

int componentSize(int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return 4;
    default:
      return 0;
  }
}

// Checks that element count-1 ends inside the view: offset + stride * (count - 1) + element.
bool fitsInView(const tg::Accessor& a, size_t stride, size_t element, size_t viewLength) {
  if (a.count == 0) return true;
  if (a.byteOffset > viewLength || viewLength - a.byteOffset < element) return false;
  return a.count - 1 <= (viewLength - a.byteOffset - element) / stride;
}

AccessorView viewAccessor(const Loader& ld, int index, const std::string& what) {
  if (!inRange(index, ld.model.accessors))
    ld.fail(what + ": accessor index " + std::to_string(index) + " out of range");
  const tg::Accessor& a = ld.model.accessors[size_t(index)];
  const std::string where = what + " (accessor " + std::to_string(index) + ")";
  if (a.sparse.isSparse) ld.fail(where + ": sparse accessors are not supported");
  AccessorView v;
  v.count = a.count;
  v.componentType = a.componentType;
  v.components = tg::GetNumComponentsInType(uint32_t(a.type));
  v.normalized = a.normalized;
  const int size = componentSize(a.componentType);
  if (size <= 0 || v.components <= 0) ld.fail(where + ": invalid componentType or type");
  const size_t element = size_t(size) * size_t(v.components);
  if (a.bufferView < 0) {
    if (a.count > kMaxZeroAccessorCount) ld.fail(where + ": implausible count");
    return v;
  }
  if (!inRange(a.bufferView, ld.model.bufferViews))
    ld.fail(where + ": bufferView index " + std::to_string(a.bufferView) + " out of range");
  const tg::BufferView& view = ld.model.bufferViews[size_t(a.bufferView)];
  v.stride = view.byteStride ? view.byteStride : element;
  if (v.stride < element) ld.fail(where + ": byteStride is smaller than one element");
  if (!fitsInView(a, v.stride, element, view.byteLength))
    ld.fail(where + ": " + std::to_string(a.count) + " elements at offset " +
            std::to_string(a.byteOffset) + " are out of range of bufferView " +
            std::to_string(a.bufferView) + " (" + std::to_string(view.byteLength) + " bytes)");
  v.data = ld.model.buffers[size_t(view.buffer)].data.data() + view.byteOffset + a.byteOffset;
  return v;
}

template <typename T>
T load(const uint8_t* p) {
  T v;
  std::memcpy(&v, p, sizeof(T));
  return v;
}

// Normalised integers as glTF 2.0 §3.11 defines them (signed: max(c / MAX, -1)).
float componentAt(const AccessorView& v, size_t i, int c) {
  if (!v.data) return 0.0f;
  const uint8_t* p = v.data + i * v.stride + size_t(c) * size_t(componentSize(v.componentType));
  switch (v.componentType) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return load<float>(p);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return v.normalized ? p[0] / 255.0f : float(p[0]);
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const float x = float(load<int8_t>(p));
      return v.normalized ? std::max(x / 127.0f, -1.0f) : x;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return v.normalized ? load<uint16_t>(p) / 65535.0f : float(load<uint16_t>(p));
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      const float x = float(load<int16_t>(p));
      return v.normalized ? std::max(x / 32767.0f, -1.0f) : x;
    }
    default:
      return float(load<uint32_t>(p));
  }
}

template <int N>
std::vector<glm::vec<N, float>> readVectors(const Loader& ld, int accessor,
                                            const std::string& what) {
  const AccessorView v = viewAccessor(ld, accessor, what);
  if (v.components != N)
    ld.fail(what + ": accessor has " + std::to_string(v.components) + " components, expected " +
            std::to_string(N));
  std::vector<glm::vec<N, float>> out(v.count);
  for (size_t i = 0; i < v.count; ++i)
    for (int c = 0; c < N; ++c) out[i][c] = componentAt(v, i, c);
  return out;
}

// glTF 2.0 §3.7.2.1: indices are unsigned byte, short or int scalars.
std::vector<uint32_t> readIndices(const Loader& ld, int accessor, const std::string& what) {
  const AccessorView v = viewAccessor(ld, accessor, what);
  const bool unsignedType = v.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                            v.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ||
                            v.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  if (v.components != 1 || !unsignedType)
    ld.fail(what + ": indices must be unsigned byte, short or int scalars");
  std::vector<uint32_t> out(v.count, 0);
  if (!v.data) return out;
  for (size_t i = 0; i < v.count; ++i) {
    const uint8_t* p = v.data + i * v.stride;
    if (v.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) out[i] = p[0];
    if (v.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) out[i] = load<uint16_t>(p);
    if (v.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) out[i] = load<uint32_t>(p);
  }
  return out;
}

// ---------------------------------------------------------------------------------------
// Textures (glTF 2.0 §3.8)

std::string textureName(const Loader& ld, int index) {
  const tg::Texture& t = ld.model.textures[size_t(index)];
  if (!t.name.empty()) return t.name;
  if (inRange(t.source, ld.model.images)) {
    const tg::Image& image = ld.model.images[size_t(t.source)];
    if (!image.name.empty()) return image.name;
    if (!image.uri.empty() && !tg::IsDataURI(image.uri)) return image.uri;
  }
  return "texture#" + std::to_string(index);
}

// The encoded file bytes of an image, or empty with 'problem' set.
std::vector<uint8_t> encodedImage(const Loader& ld, const tg::Image& image, std::string& problem) {
  if (image.bufferView >= 0) {
    // Range-checked by checkBufferViews; tinygltf already refused an out-of-range index.
    const tg::BufferView& view = ld.model.bufferViews[size_t(image.bufferView)];
    const uint8_t* begin = ld.model.buffers[size_t(view.buffer)].data.data() + view.byteOffset;
    return std::vector<uint8_t>(begin, begin + view.byteLength);
  }
  if (image.image.empty()) {
    const bool external = !image.uri.empty() && !tg::IsDataURI(image.uri);
    std::error_code ec;
    if (external && !fs::exists(fs::path(ld.baseDir) / image.uri, ec))
      problem = "file not found";
    else
      problem = external ? "cannot read the file" : "no image data";
  }
  return image.image;
}

// PNG and JPEG textures are decoded with stb_image, not OpenImageIO: OpenImageIO's PNG
// reader leaves libpng's default error handler in place, which prints its own "libpng
// error: ..." line on stderr before ours, and it premultiplies colour by alpha on read,
// while glTF colours are straight alpha (glTF 2.0 §3.9.2). stb_image returns straight
// RGBA8 (gray replicated, alpha 255 when absent), row 0 at the top, and only a reason.
// Throws InputError with the bare problem.
void decodeStraightRgba8(const std::vector<uint8_t>& bytes, Texture& texture) {
  // glTF 2.0's core image formats (§3.9.2), told apart by their magic bytes.
  const bool png = bytes.size() >= 8 && std::memcmp(bytes.data(), "\x89PNG\r\n\x1a\n", 8) == 0;
  const bool jpeg = bytes.size() >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF;
  if (!png && !jpeg) throw InputError("", "not a PNG or JPEG image (the formats glTF 2.0 allows)");
  if (bytes.size() > size_t(std::numeric_limits<int>::max()))
    throw InputError("", "image larger than 2 GiB");
  const char* format = png ? "PNG" : "JPEG";
  const auto load = [&](int& w, int& h) {
    int channels = 0;
    return std::unique_ptr<stbi_uc, void (*)(void*)>(
        stbi_load_from_memory(bytes.data(), int(bytes.size()), &w, &h, &channels, 4),
        stbi_image_free);
  };
  int w = 0, h = 0, channels = 0;
  // The header first, so that a size claimed to exhaust memory is refused unallocated. Its
  // failure reason is the last format stb tried; the full decode gives the format's own.
  if (!stbi_info_from_memory(bytes.data(), int(bytes.size()), &w, &h, &channels)) {
    load(w, h);
    throw InputError("", std::string("corrupt ") + format + " image: " + stbi_failure_reason());
  }
  if (w <= 0 || h <= 0 || int64_t(w) * h > (int64_t(1) << 28))
    throw InputError("", "implausible image size " + std::to_string(w) + "x" + std::to_string(h));
  const auto pixels = load(w, h);
  if (!pixels)
    throw InputError(
        "", std::string("corrupt or truncated ") + format + " image: " + stbi_failure_reason());
  texture.width = w;
  texture.height = h;
  texture.rgba.assign(pixels.get(), pixels.get() + size_t(w) * size_t(h) * 4);
}

Texture::Wrap wrapMode(int samplerWrap) {
  switch (samplerWrap) {
    case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE:
      return Texture::Wrap::Clamp;
    case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT:
      return Texture::Wrap::Mirror;
    default:
      return Texture::Wrap::Repeat;
  }
}

void applySampler(const Loader& ld, int sampler, Texture& texture) {
  if (sampler < 0) return;  // §3.8.4: no sampler means repeat wrapping, auto filtering
  const tg::Sampler& s = ld.model.samplers[size_t(sampler)];
  texture.wrapS = wrapMode(s.wrapS);
  texture.wrapT = wrapMode(s.wrapT);
  texture.nearest = s.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST;
}

// Decodes one glTF texture. A missing or undecodable image is an error naming the file and
// the texture (bad input, as a broken buffer is); a texture with no image source at all is
// legal glTF and only warned about: the material's factor stands alone.
std::optional<Texture> loadTexture(Loader& ld, int index, const std::string& where) {
  const tg::Texture& gt = ld.model.textures[size_t(index)];
  if (gt.sampler >= 0 && !inRange(gt.sampler, ld.model.samplers))
    ld.fail(where + ": sampler index " + std::to_string(gt.sampler) + " out of range");
  if (gt.source >= 0 && !inRange(gt.source, ld.model.images))
    ld.fail(where + ": image index " + std::to_string(gt.source) + " out of range");
  Texture texture;
  texture.name = textureName(ld, index);
  if (gt.source < 0) {
    ld.warn("texture " + named(texture.name) + ": no image source, using the material factor");
    return std::nullopt;
  }
  std::string problem;
  const std::vector<uint8_t> bytes = encodedImage(ld, ld.model.images[size_t(gt.source)], problem);
  if (!problem.empty()) ld.fail("texture " + named(texture.name) + ": " + problem);
  try {
    decodeStraightRgba8(bytes, texture);
  } catch (const InputError& e) {
    ld.fail("texture " + named(texture.name) + ": " + firstLine(e.what()));
  }
  applySampler(ld, gt.sampler, texture);
  return texture;
}

int sceneTexture(Loader& ld, int index, const std::string& where) {
  if (!inRange(index, ld.model.textures))
    ld.fail(where + ": texture index " + std::to_string(index) + " out of range");
  int& slot = ld.textures[size_t(index)];
  if (slot != kTextureNotLoaded) return slot;
  slot = -1;
  std::optional<Texture> texture = loadTexture(ld, index, where);
  if (texture) {
    slot = int(ld.scene.textures.size());
    ld.scene.textures.push_back(std::move(*texture));
  }
  return slot;
}

float numberOr(const tg::Value& object, const char* key, float fallback) {
  if (!object.Has(key) || !object.Get(key).IsNumber()) return fallback;
  return float(object.Get(key).GetNumberAsDouble());
}

glm::vec2 vec2Or(const tg::Value& object, const char* key, glm::vec2 fallback) {
  if (!object.Has(key)) return fallback;
  const tg::Value& a = object.Get(key);
  if (!a.IsArray() || a.ArrayLen() != 2 || !a.Get(0).IsNumber() || !a.Get(1).IsNumber())
    return fallback;
  return {float(a.Get(0).GetNumberAsDouble()), float(a.Get(1).GetNumberAsDouble())};
}

// KHR_texture_transform, including its texCoord override.
void applyTextureTransform(const tg::ExtensionMap& extensions, TextureRef& ref) {
  const auto it = extensions.find("KHR_texture_transform");
  if (it == extensions.end() || !it->second.IsObject()) return;
  const tg::Value& t = it->second;
  ref.transform.offset = vec2Or(t, "offset", glm::vec2(0.0f));
  ref.transform.rotation = numberOr(t, "rotation", 0.0f);
  ref.transform.scale = vec2Or(t, "scale", glm::vec2(1.0f));
  if (t.Has("texCoord") && t.Get("texCoord").IsNumber())
    ref.texCoord = t.Get("texCoord").GetNumberAsInt();
}

template <typename Info>
TextureRef textureRef(Loader& ld, const Info& info, const std::string& where) {
  TextureRef ref;
  if (info.index < 0) return ref;
  ref.texCoord = info.texCoord;
  applyTextureTransform(info.extensions, ref);
  const TextureTransform& t = ref.transform;
  if (!(std::isfinite(t.offset.x) && std::isfinite(t.offset.y) && std::isfinite(t.rotation) &&
        std::isfinite(t.scale.x) && std::isfinite(t.scale.y)))
    ld.fail(where + ": KHR_texture_transform offset, rotation and scale must be finite");
  if (ref.texCoord < 0 || ref.texCoord > 1) {
    ld.warn(where + ": uses TEXCOORD_" + std::to_string(ref.texCoord) +
            ", only 0 and 1 are supported; using the material factor");
    return TextureRef{};
  }
  ref.texture = sceneTexture(ld, info.index, where);
  return ref;
}

// ---------------------------------------------------------------------------------------
// Materials (glTF 2.0 §3.9)

glm::vec4 vec4Or(const std::vector<double>& v, glm::vec4 fallback) {
  return v.size() == 4 ? glm::vec4(float(v[0]), float(v[1]), float(v[2]), float(v[3])) : fallback;
}

glm::vec3 vec3Or(const std::vector<double>& v, glm::vec3 fallback) {
  return v.size() == 3 ? glm::vec3(float(v[0]), float(v[1]), float(v[2])) : fallback;
}

float emissiveStrength(const tg::Material& gm) {
  const auto it = gm.extensions.find("KHR_materials_emissive_strength");
  if (it == gm.extensions.end() || !it->second.IsObject()) return 1.0f;
  return numberOr(it->second, "emissiveStrength", 1.0f);
}

const tg::Value* materialExtension(const tg::Material& gm, const char* name) {
  const auto it = gm.extensions.find(name);
  return it != gm.extensions.end() && it->second.IsObject() ? &it->second : nullptr;
}

glm::vec3 vec3Or(const tg::Value& object, const char* key, glm::vec3 fallback) {
  if (!object.Has(key)) return fallback;
  const tg::Value& a = object.Get(key);
  if (!a.IsArray() || a.ArrayLen() != 3) return fallback;
  glm::vec3 v;
  for (int k = 0; k < 3; ++k) {
    if (!a.Get(k).IsNumber()) return fallback;
    v[k] = float(a.Get(k).GetNumberAsDouble());
  }
  return v;
}

// A textureInfo object inside an extension, as tinygltf parses the core ones.
TextureRef extensionTexture(Loader& ld, const tg::Value& ext, const char* key,
                            const std::string& where) {
  tg::TextureInfo info;
  if (!ext.Has(key) || !ext.Get(key).IsObject()) return TextureRef{};
  const tg::Value& t = ext.Get(key);
  if (t.Has("index") && t.Get("index").IsInt()) info.index = t.Get("index").GetNumberAsInt();
  if (t.Has("texCoord") && t.Get("texCoord").IsInt())
    info.texCoord = t.Get("texCoord").GetNumberAsInt();
  if (t.Has("extensions") && t.Get("extensions").IsObject()) {
    const tg::Value& e = t.Get("extensions");
    for (const std::string& name : e.Keys()) info.extensions[name] = e.Get(name);
  }
  return textureRef(ld, info, where + " " + key);
}

// KHR_materials_ior, _specular, _transmission and _volume (their specifications' defaults).
void convertDielectric(Loader& ld, const tg::Material& gm, Material& m, const std::string& where) {
  if (const tg::Value* e = materialExtension(gm, "KHR_materials_ior"))
    m.ior = numberOr(*e, "ior", 1.5f);
  if (const tg::Value* e = materialExtension(gm, "KHR_materials_specular")) {
    m.specularFactor = numberOr(*e, "specularFactor", 1.0f);
    m.specularColorFactor = vec3Or(*e, "specularColorFactor", glm::vec3(1.0f));
    m.specularTexture = extensionTexture(ld, *e, "specularTexture", where);
    m.specularColorTexture = extensionTexture(ld, *e, "specularColorTexture", where);
  }
  if (const tg::Value* e = materialExtension(gm, "KHR_materials_transmission")) {
    m.transmissionFactor = numberOr(*e, "transmissionFactor", 0.0f);
    m.transmissionTexture = extensionTexture(ld, *e, "transmissionTexture", where);
  }
  m.unlit = materialExtension(gm, "KHR_materials_unlit") != nullptr;
  if (const tg::Value* e = materialExtension(gm, "KHR_materials_volume")) {
    m.thicknessFactor = numberOr(*e, "thicknessFactor", 0.0f);
    m.attenuationColor = vec3Or(*e, "attenuationColor", glm::vec3(1.0f));
    m.attenuationDistance = numberOr(*e, "attenuationDistance", 0.0f);
    if (e->Has("thicknessTexture"))
      ld.warn(where +
              ": KHR_materials_volume thicknessTexture is not used (only whether the "
              "thickness is 0: a thin wall, or a volume)");
  }
}

// KHR_materials_sheen and _clearcoat (their specifications' defaults), with the coat's own
// normal map and its scale.
void convertLayers(Loader& ld, const tg::Material& gm, Material& m, const std::string& where) {
  if (const tg::Value* e = materialExtension(gm, "KHR_materials_sheen")) {
    m.sheenColorFactor = vec3Or(*e, "sheenColorFactor", glm::vec3(0.0f));
    m.sheenRoughnessFactor = numberOr(*e, "sheenRoughnessFactor", 0.0f);
    m.sheenColorTexture = extensionTexture(ld, *e, "sheenColorTexture", where);
    m.sheenRoughnessTexture = extensionTexture(ld, *e, "sheenRoughnessTexture", where);
  }
  if (const tg::Value* e = materialExtension(gm, "KHR_materials_clearcoat")) {
    m.clearcoatFactor = numberOr(*e, "clearcoatFactor", 0.0f);
    m.clearcoatRoughnessFactor = numberOr(*e, "clearcoatRoughnessFactor", 0.0f);
    m.clearcoatTexture = extensionTexture(ld, *e, "clearcoatTexture", where);
    m.clearcoatRoughnessTexture = extensionTexture(ld, *e, "clearcoatRoughnessTexture", where);
    m.clearcoatNormalTexture = extensionTexture(ld, *e, "clearcoatNormalTexture", where);
    if (e->Has("clearcoatNormalTexture") && e->Get("clearcoatNormalTexture").IsObject() &&
        e->Get("clearcoatNormalTexture").Has("scale"))
      m.clearcoatNormalScale = numberOr(e->Get("clearcoatNormalTexture"), "scale", 1.0f);
  }
}

AlphaMode alphaMode(Loader& ld, const tg::Material& gm, const std::string& where) {
  if (gm.alphaMode == "MASK") return AlphaMode::Mask;
  if (gm.alphaMode == "BLEND") return AlphaMode::Blend;  // stochastic coverage
  if (gm.alphaMode != "OPAQUE") ld.warn(where + ": unknown alphaMode '" + gm.alphaMode + "'");
  return AlphaMode::Opaque;
}

void convertTextures(Loader& ld, const tg::Material& gm, Material& m, const std::string& where) {
  const tg::PbrMetallicRoughness& pbr = gm.pbrMetallicRoughness;
  m.baseColorTexture = textureRef(ld, pbr.baseColorTexture, where + " baseColorTexture");
  m.metallicRoughnessTexture =
      textureRef(ld, pbr.metallicRoughnessTexture, where + " metallicRoughnessTexture");
  m.normalTexture = textureRef(ld, gm.normalTexture, where + " normalTexture");
  m.occlusionTexture = textureRef(ld, gm.occlusionTexture, where + " occlusionTexture");
  m.emissiveTexture = textureRef(ld, gm.emissiveTexture, where + " emissiveTexture");
}

bool within(float v, float lo, float hi) {
  return v >= lo && v <= hi;  // false for NaN
}

// The extensions' ranges: ior 0 or in [1, 10] (KHR_materials_ior allows 0 and any value
// >= 1; above 10 no known material, and F0 passes 0.67), specular strength and
// transmission in [0, 1], specular colour >= 0 (values above 1 are the extension's way to
// reach f0 1 at low ior; the BSDF clamps f0), thickness >= 0, attenuation colour in [0, 1]
// and distance > 0 when given.
void checkDielectric(const Loader& ld, const Material& m, const std::string& what) {
  if (!(m.ior == 0.0f || within(m.ior, 1, 10)))
    ld.fail(what + "KHR_materials_ior ior must be 0 or in [1, 10]");
  const glm::vec3 sc = m.specularColorFactor, ac = m.attenuationColor;
  if (!within(m.specularFactor, 0, 1) ||
      !(within(sc.r, 0, 1e6f) && within(sc.g, 0, 1e6f) && within(sc.b, 0, 1e6f)))
    ld.fail(what + "KHR_materials_specular factor must be in [0, 1], its colour >= 0");
  if (!within(m.transmissionFactor, 0, 1))
    ld.fail(what + "KHR_materials_transmission factor must be in [0, 1]");
  const glm::vec3 sh = m.sheenColorFactor;
  if (!(within(sh.r, 0, 1) && within(sh.g, 0, 1) && within(sh.b, 0, 1)) ||
      !within(m.sheenRoughnessFactor, 0, 1))
    ld.fail(what + "KHR_materials_sheen colour and roughness must be in [0, 1]");
  if (!within(m.clearcoatFactor, 0, 1) || !within(m.clearcoatRoughnessFactor, 0, 1))
    ld.fail(what + "KHR_materials_clearcoat factor and roughness must be in [0, 1]");
  if (!within(m.thicknessFactor, 0, 1e30f) ||
      !(within(ac.r, 0, 1) && within(ac.g, 0, 1) && within(ac.b, 0, 1)) ||
      !(m.attenuationDistance == 0.0f || within(m.attenuationDistance, 1e-30f, 1e30f)))
    ld.fail(what +
            "KHR_materials_volume thickness must be >= 0, attenuation colour in [0, 1] "
            "and distance > 0");
}

// glTF 2.0 §5.19-5.22's ranges for what reflects light: base colour, metallic, roughness
// and occlusion strength in [0, 1] (above 1 a surface reflects more than it receives, and
// each bounce multiplies the excess), alpha cutoff >= 0. Emission is radiance, not a ratio:
// any emissive factor x strength >= 0 up to 1e20 is taken (files written before
// KHR_materials_emissive_strength put HDR emission in the factor), as lights are.
void checkMaterial(const Loader& ld, const Material& m) {
  const std::string what = "material " + named(m.name) + ": ";
  const glm::vec4 c = m.baseColorFactor;
  if (!(within(c.r, 0, 1) && within(c.g, 0, 1) && within(c.b, 0, 1) && within(c.a, 0, 1)))
    ld.fail(what + "baseColorFactor must be in [0, 1]");
  if (!within(m.metallicFactor, 0, 1) || !within(m.roughnessFactor, 0, 1))
    ld.fail(what + "metallicFactor and roughnessFactor must be in [0, 1]");
  if (!within(m.occlusionStrength, 0, 1)) ld.fail(what + "occlusion strength must be in [0, 1]");
  if (!within(m.alphaCutoff, 0, 1e30f)) ld.fail(what + "alphaCutoff must be >= 0");
  if (!std::isfinite(m.normalScale) || !std::isfinite(m.clearcoatNormalScale))
    ld.fail(what + "normal scale must be finite");
  const glm::vec3 e = m.emissiveFactor;
  const float brightest = std::max({e.r, e.g, e.b}) * m.emissiveStrength;
  if (!(e.r >= 0 && e.g >= 0 && e.b >= 0 && m.emissiveStrength >= 0 && brightest <= 1e20f))
    ld.fail(what + "emissive factor and strength must be >= 0 with their product at most 1e20");
  checkDielectric(ld, m, what);
}

Material convertMaterial(Loader& ld, const tg::Material& gm, size_t index) {
  Material m;
  m.name = gm.name.empty() ? "material#" + std::to_string(index) : gm.name;
  const std::string where = "material " + named(m.name);
  const tg::PbrMetallicRoughness& pbr = gm.pbrMetallicRoughness;
  m.baseColorFactor = vec4Or(pbr.baseColorFactor, glm::vec4(1.0f));
  m.metallicFactor = float(pbr.metallicFactor);
  m.roughnessFactor = float(pbr.roughnessFactor);
  m.emissiveFactor = vec3Or(gm.emissiveFactor, glm::vec3(0.0f));
  m.emissiveStrength = emissiveStrength(gm);
  m.normalScale = float(gm.normalTexture.scale);
  m.occlusionStrength = float(gm.occlusionTexture.strength);
  m.alphaMode = alphaMode(ld, gm, where);
  m.alphaCutoff = float(gm.alphaCutoff);
  m.doubleSided = gm.doubleSided;
  convertDielectric(ld, gm, m, where);
  convertLayers(ld, gm, m, where);
  checkMaterial(ld, m);
  convertTextures(ld, gm, m, where);
  return m;
}

// The glTF default material (§3.9.6) is appended only when a primitive needs it.
int materialIndex(Loader& ld, int material, const std::string& where) {
  if (material < 0) {
    if (ld.defaultMaterial < 0) {
      ld.defaultMaterial = int(ld.scene.materials.size());
      ld.scene.materials.push_back(Material{});
      ld.scene.materials.back().name = "default";
    }
    return ld.defaultMaterial;
  }
  if (!inRange(material, ld.model.materials))
    ld.fail(where + ": material index " + std::to_string(material) + " out of range");
  return material;
}

// ---------------------------------------------------------------------------------------
// Meshes (glTF 2.0 §3.7)

// Strips and fans to lists with the winding rules of §3.7.2.1.
std::vector<uint32_t> toTriangleList(const std::vector<uint32_t>& v, int mode) {
  if (mode == TINYGLTF_MODE_TRIANGLES) return v;
  std::vector<uint32_t> out;
  for (size_t i = 0; i + 2 < v.size(); ++i) {
    if (mode == TINYGLTF_MODE_TRIANGLE_STRIP)
      out.insert(out.end(), {v[i], v[i + 1 + i % 2], v[i + 2 - i % 2]});
    else
      out.insert(out.end(), {v[i + 1], v[i + 2], v[0]});
  }
  return out;
}

void checkCount(const Loader& ld, size_t count, size_t vertices, const std::string& what) {
  if (count != vertices)
    ld.fail(what + ": has " + std::to_string(count) + " entries for " + std::to_string(vertices) +
            " vertices");
}

// glTF 2.0 §3.7.3.3: JOINTS_0 are unsigned byte or short indices into the skin's joints;
// WEIGHTS_0 float or normalised unsigned, non-negative. They are normalised to sum 1 here
// (exporters round them); a vertex with no weight at all cannot be skinned.
void readSkinAttributes(const Loader& ld, int joints, int weights, Mesh& mesh,
                        const std::string& where) {
  if (joints < 0 || weights < 0) ld.fail(where + ": JOINTS_0 and WEIGHTS_0 come together");
  const AccessorView jv = viewAccessor(ld, joints, where + " JOINTS_0");
  if (jv.normalized || (jv.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
                        jv.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT))
    ld.fail(where + " JOINTS_0: must be unsigned byte or short, not normalized");
  const size_t n = mesh.positions.size();
  MeshSkinning& s = mesh.skinning;
  for (const glm::vec4& j : readVectors<4>(ld, joints, where + " JOINTS_0"))
    s.joints.emplace_back(j);
  s.weights = readVectors<4>(ld, weights, where + " WEIGHTS_0");
  checkCount(ld, s.joints.size(), n, where + " JOINTS_0");
  checkCount(ld, s.weights.size(), n, where + " WEIGHTS_0");
  for (size_t v = 0; v < n; ++v) {
    glm::vec4& w = s.weights[v];
    const float sum = w.x + w.y + w.z + w.w;
    if (!(w.x >= 0.0f && w.y >= 0.0f && w.z >= 0.0f && w.w >= 0.0f) || !(sum > 0.0f) ||
        !std::isfinite(sum))
      ld.fail(where + " WEIGHTS_0: vertex " + std::to_string(v) +
              " has negative, non-finite or no weights");
    w /= sum;
  }
}

void readAttributes(const Loader& ld, const tg::Primitive& prim, Mesh& mesh,
                    const std::string& where) {
  const auto find = [&](const char* name) {
    const auto it = prim.attributes.find(name);
    return it == prim.attributes.end() ? -1 : it->second;
  };
  if (find("POSITION") < 0) ld.fail(where + ": has no POSITION attribute");
  mesh.positions = readVectors<3>(ld, find("POSITION"), where + " POSITION");
  const size_t n = mesh.positions.size();
  if (find("NORMAL") >= 0) mesh.normals = readVectors<3>(ld, find("NORMAL"), where + " NORMAL");
  if (find("TANGENT") >= 0) mesh.tangents = readVectors<4>(ld, find("TANGENT"), where + " TANGENT");
  if (find("TEXCOORD_0") >= 0) mesh.uv0 = readVectors<2>(ld, find("TEXCOORD_0"), where + " UV0");
  if (find("TEXCOORD_1") >= 0) mesh.uv1 = readVectors<2>(ld, find("TEXCOORD_1"), where + " UV1");
  if (!mesh.normals.empty()) checkCount(ld, mesh.normals.size(), n, where + " NORMAL");
  if (!mesh.tangents.empty()) checkCount(ld, mesh.tangents.size(), n, where + " TANGENT");
  if (!mesh.uv0.empty()) checkCount(ld, mesh.uv0.size(), n, where + " TEXCOORD_0");
  if (!mesh.uv1.empty()) checkCount(ld, mesh.uv1.size(), n, where + " TEXCOORD_1");
  if (find("JOINTS_0") >= 0 || find("WEIGHTS_0") >= 0)
    readSkinAttributes(ld, find("JOINTS_0"), find("WEIGHTS_0"), mesh, where);
}

// Returns false if any normal has zero length (it cannot be normalised). Scaled by its
// largest component first, so that neither a huge normal (1e30: its squared length
// overflows to inf and n / inf = 0) nor a tiny one (1e-30: it underflows to 0) is lost.
bool normalizeAll(std::vector<glm::vec3>& normals) {
  for (glm::vec3& n : normals) {
    const float largest = std::max({std::abs(n.x), std::abs(n.y), std::abs(n.z)});
    if (!(largest > 0.0f)) return false;
    n /= largest;
    n /= glm::length(n);
  }
  return true;
}

void checkTangents(const Loader& ld, const Mesh& mesh) {
  for (size_t i = 0; i < mesh.tangents.size(); ++i) {
    const glm::vec4& t = mesh.tangents[i];
    if (!std::isfinite(t.x) || !std::isfinite(t.y) || !std::isfinite(t.z) || !std::isfinite(t.w))
      ld.fail("mesh " + named(mesh.name) + ": non-finite TANGENT at vertex " + std::to_string(i));
  }
}

// Runs after validateMesh, so every index is in range.
void finishShading(Loader& ld, Mesh& mesh) {
  checkTangents(ld, mesh);
  if (!mesh.normals.empty() && !normalizeAll(mesh.normals)) {
    ld.warn("mesh " + named(mesh.name) + ": zero-length normals, using flat normals");
    mesh.normals.clear();
  }
  if (mesh.normals.empty()) makeFlatShaded(mesh);  // §3.7.2.1: flat normals when absent
  const Material& material = ld.scene.materials[size_t(mesh.material)];
  const bool normalMapped =
      material.normalTexture.valid() || material.clearcoatNormalTexture.valid();
  if (normalMapped && mesh.tangents.empty()) computeTangents(mesh);
}

// KHR_draco_mesh_compression: the primitive's attributes and triangle list from its Draco
// bitstream (core/gltf_draco.h); the buffer view's range was checked by checkBufferViews.
std::vector<uint32_t> readDracoPrimitive(const Loader& ld, const tg::Value& ext, Mesh& mesh,
                                         const std::string& where) {
  const std::string what = where + " KHR_draco_mesh_compression";
  const tg::Value& view = ext.Get("bufferView");
  if (!view.IsInt() || !inRange(view.GetNumberAsInt(), ld.model.bufferViews))
    ld.fail(what + ": bufferView missing or out of range");
  std::map<std::string, int> ids;
  const tg::Value& attributes = ext.Get("attributes");
  if (!attributes.IsObject()) ld.fail(what + ": attributes missing");
  for (const std::string& name : attributes.Keys())
    if (attributes.Get(name).IsInt()) ids[name] = attributes.Get(name).GetNumberAsInt();
  if (!ids.count("POSITION")) ld.fail(what + ": has no POSITION attribute");
  const tg::BufferView& bv = ld.model.bufferViews[size_t(view.GetNumberAsInt())];
  const uint8_t* bytes = ld.model.buffers[size_t(bv.buffer)].data.data() + bv.byteOffset;
  DracoGeometry g;
  std::string problem;
  if (!decodeDraco(bytes, bv.byteLength, ids, g, problem)) ld.fail(what + ": " + problem);
  mesh.positions = std::move(g.positions);
  mesh.normals = std::move(g.normals);
  mesh.tangents = std::move(g.tangents);
  mesh.uv0 = std::move(g.uv0);
  mesh.uv1 = std::move(g.uv1);
  return g.indices;
}

std::string primitiveName(const tg::Mesh& gm, int meshIndex, size_t primitive) {
  std::string name = gm.name.empty() ? "mesh#" + std::to_string(meshIndex) : gm.name;
  if (gm.primitives.size() > 1) name += "/" + std::to_string(primitive);
  return name;
}

std::optional<Mesh> convertPrimitive(Loader& ld, int meshIndex, size_t p) {
  const tg::Mesh& gm = ld.model.meshes[size_t(meshIndex)];
  const tg::Primitive& prim = gm.primitives[p];
  Mesh mesh;
  mesh.name = primitiveName(gm, meshIndex, p);
  const std::string where = "mesh " + named(mesh.name);
  const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
  if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
      mode != TINYGLTF_MODE_TRIANGLE_FAN) {
    ld.warn(where + ": primitive mode " + std::to_string(mode) +
            " (points or lines) skipped, only triangles are rendered");
    return std::nullopt;
  }
  std::vector<uint32_t> indices;
  if (const auto draco = prim.extensions.find("KHR_draco_mesh_compression");
      draco != prim.extensions.end()) {
    indices = readDracoPrimitive(ld, draco->second, mesh, where);
  } else {
    readAttributes(ld, prim, mesh, where);
    indices.resize(mesh.positions.size());
    for (size_t i = 0; i < indices.size(); ++i) indices[i] = uint32_t(i);
    if (prim.indices >= 0) indices = readIndices(ld, prim.indices, where + " indices");
  }
  mesh.indices = toTriangleList(indices, mode);
  mesh.material = materialIndex(ld, prim.material, where);
  validateMesh(mesh, ld.path);
  finishShading(ld, mesh);
  validateMesh(mesh, ld.path);
  return mesh;
}

const std::vector<int>& sceneMeshes(Loader& ld, int meshIndex) {
  if (ld.meshConverted[size_t(meshIndex)]) return ld.meshes[size_t(meshIndex)];
  const tg::Mesh& gm = ld.model.meshes[size_t(meshIndex)];
  std::vector<int>& out = ld.meshes[size_t(meshIndex)];
  for (size_t p = 0; p < gm.primitives.size(); ++p) {
    std::optional<Mesh> mesh = convertPrimitive(ld, meshIndex, p);
    if (!mesh) continue;
    out.push_back(int(ld.scene.meshes.size()));
    ld.scene.meshes.push_back(std::move(*mesh));
  }
  ld.meshConverted[size_t(meshIndex)] = true;
  return out;
}

// ---------------------------------------------------------------------------------------
// Nodes, lights and cameras (glTF 2.0 §3.5)

template <typename T>
bool isFinite(const glm::mat<4, 4, T>& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) return false;
  return true;
}

glm::dvec3 dvec3Or(const std::vector<double>& v, glm::dvec3 fallback) {
  return v.size() == 3 ? glm::dvec3(v[0], v[1], v[2]) : fallback;
}

// Node transforms are composed in double (glTF stores them so): a file 1e7 m out keeps
// its parts' relative placement to the micrometre until storePlacement re-bases it.
glm::dmat4 trsMatrix(const Loader& ld, const tg::Node& n, const std::string& where) {
  const bool badSizes = (!n.translation.empty() && n.translation.size() != 3) ||
                        (!n.rotation.empty() && n.rotation.size() != 4) ||
                        (!n.scale.empty() && n.scale.size() != 3);
  if (badSizes) ld.fail(where + ": translation, rotation or scale has the wrong length");
  glm::dmat4 m(1.0);
  if (!n.translation.empty()) m = glm::translate(m, dvec3Or(n.translation, glm::dvec3(0.0)));
  if (!n.rotation.empty()) {
    // glTF stores quaternions as (x, y, z, w); glm's constructor takes w first.
    const glm::dquat q(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]);
    // A unit quaternion (§5.25); slightly off ones, as exporters write, are normalised.
    if (!(glm::length(q) > 1e-6)) ld.fail(where + ": rotation is not a unit quaternion");
    m = m * glm::mat4_cast(glm::normalize(q));
  }
  if (!n.scale.empty()) m = glm::scale(m, dvec3Or(n.scale, glm::dvec3(1.0)));
  return m;
}

glm::dmat4 localTransform(const Loader& ld, const tg::Node& n, const std::string& where) {
  glm::dmat4 m(1.0);
  if (!n.matrix.empty()) {
    if (n.matrix.size() != 16) ld.fail(where + ": matrix must have 16 numbers");
    for (int i = 0; i < 16; ++i) glm::value_ptr(m)[i] = n.matrix[size_t(i)];  // column-major
  } else {
    m = trsMatrix(ld, n, where);
  }
  if (!isFinite(m)) ld.fail(where + ": non-finite transform");
  return m;
}

// KHR_lights_punctual's ranges: colour and intensity >= 0, range > 0 when given, and
// 0 <= inner < outer <= pi/2 for spots. Above 1e20 (cd or lux; sunlight is ~1e5 lux) the
// tracer's products of intensity, BSDF (up to ~1e6 at the smallest roughness) and inverse
// squared distance leave float range: NaN samples, not light.
void checkLight(const Loader& ld, const Light& l, bool spot) {
  const std::string what = "light " + named(l.name) + ": ";
  const float brightest = std::max({l.color.r, l.color.g, l.color.b}) * l.intensity;
  const bool colorOk = l.color.r >= 0.0f && l.color.g >= 0.0f && l.color.b >= 0.0f;
  if (!colorOk || !(l.intensity >= 0.0f) || !(brightest <= 1e20f))
    ld.fail(what + "colour and intensity must be >= 0 with colour x intensity at most 1e20");
  if (!(l.range >= 0.0f) || !std::isfinite(l.range)) ld.fail(what + "range must be > 0 when given");
  if (spot && !(l.innerConeAngle >= 0.0f && l.innerConeAngle < l.outerConeAngle &&
                l.outerConeAngle <= glm::half_pi<float>() + 1e-6f))
    ld.fail(what + "spot cone angles must be 0 <= inner < outer <= pi/2");
}

Light convertLight(Loader& ld, const tg::Light& gl, const std::string& name) {
  Light light;
  light.name = name;
  if (gl.type == "spot") light.type = Light::Type::Spot;
  if (gl.type == "directional") light.type = Light::Type::Directional;
  if (gl.type != "point" && gl.type != "spot" && gl.type != "directional")
    ld.warn("light " + named(name) + ": unknown type '" + gl.type + "', treated as a point light");
  light.color = vec3Or(gl.color, glm::vec3(1.0f));
  light.intensity = float(gl.intensity);
  light.range = float(gl.range);
  light.innerConeAngle = float(gl.spot.innerConeAngle);
  light.outerConeAngle = float(gl.spot.outerConeAngle);
  checkLight(ld, light, gl.type == "spot");
  return light;
}

void addLight(Loader& ld, const tg::Node& node, const glm::dmat4& world, const std::string& where) {
  const auto it = node.extensions.find("KHR_lights_punctual");
  if (it == node.extensions.end()) return;
  const tg::Value& ext = it->second;
  if (!ext.IsObject() || !ext.Has("light") || !ext.Get("light").IsNumber())
    ld.fail(where + ": KHR_lights_punctual without a light index");
  const int index = ext.Get("light").GetNumberAsInt();
  if (!inRange(index, ld.model.lights))
    ld.fail(where + ": light index " + std::to_string(index) + " out of range");
  const tg::Light& gl = ld.model.lights[size_t(index)];
  Light light = convertLight(ld, gl, gl.name.empty() ? "light#" + std::to_string(index) : gl.name);
  // KHR_lights_punctual: lights sit at the node origin and shine along the node's -Z.
  light.position = glm::vec3(world[3]);
  light.direction = glm::vec3(glm::normalize(glm::dmat3(world) * glm::dvec3(0.0, 0.0, -1.0)));
  ld.scene.lights.push_back(light);
  ld.placed.lights.push_back(glm::dvec3(world[3]));
}

glm::quat rotationOf(const glm::mat4& world) {
  glm::mat3 r(world);
  for (int c = 0; c < 3; ++c) r[c] = glm::normalize(r[c]);  // drop the node's scale
  return glm::normalize(glm::quat_cast(r));
}

void addCamera(Loader& ld, const tg::Node& node, const glm::dmat4& world,
               const std::string& where) {
  if (node.camera < 0) return;
  if (!inRange(node.camera, ld.model.cameras))
    ld.fail(where + ": camera index " + std::to_string(node.camera) + " out of range");
  const tg::Camera& gc = ld.model.cameras[size_t(node.camera)];
  Camera camera;
  camera.name = gc.name.empty() ? "camera#" + std::to_string(node.camera) : gc.name;
  if (gc.type != "perspective") {
    ld.warn("camera " + named(camera.name) + ": only perspective cameras are supported; skipped");
    return;
  }
  // glTF 2.0 §5.13: 0 < yfov (< pi for a picture), znear > 0, zfar > znear when given;
  // checked on the float values the renderer uses (a yfov of 1e-46 is 0 as a float, and
  // one below ~1e-38 has an infinite 1 / tan(yfov / 2)).
  const tg::PerspectiveCamera& p = gc.perspective;
  camera.yfov = float(p.yfov);
  camera.aspect = float(p.aspectRatio);
  camera.znear = float(p.znear);
  camera.zfar = float(p.zfar);
  if (!(camera.yfov > 0.0f && camera.yfov < glm::pi<float>()) ||
      !std::isfinite(1.0f / std::tan(0.5f * camera.yfov)) ||
      !(camera.znear >= std::numeric_limits<float>::min()) || !std::isfinite(camera.znear) ||
      !(camera.aspect >= 0.0f) || !std::isfinite(camera.aspect) || !std::isfinite(camera.zfar) ||
      (camera.zfar != 0.0f && !(camera.zfar > camera.znear)))
    ld.fail("camera " + named(camera.name) +
            ": needs 0 < yfov < pi, znear > 0 and zfar > znear (or none)");
  camera.position = glm::vec3(world[3]);
  camera.orientation = rotationOf(glm::mat4(world));
  ld.scene.cameras.push_back(camera);
  ld.placed.cameras.push_back(glm::dvec3(world[3]));
}

void addMeshInstances(Loader& ld, const tg::Node& node, const glm::dmat4& world,
                      const std::string& where, const std::string& name) {
  if (node.mesh < 0) return;
  if (!inRange(node.mesh, ld.model.meshes))
    ld.fail(where + ": mesh index " + std::to_string(node.mesh) + " out of range");
  if (node.skin >= 0 && !inRange(node.skin, ld.model.skins))
    ld.fail(where + ": skin index " + std::to_string(node.skin) + " out of range");
  for (int mesh : sceneMeshes(ld, node.mesh)) {
    if (node.skin >= 0) ld.skinnedInstances.push_back({int(ld.scene.instances.size()), node.skin});
    Instance instance;
    instance.mesh = mesh;
    instance.transform = instance.previousTransform = glm::mat4(world);  // storePlacement
    instance.node = name;
    ld.scene.instances.push_back(instance);
    ld.placed.instances.push_back(world);
  }
}

// Places one node: checks it, adds its mesh instances, light and camera; returns its world
// transform.
// The node's rest pose for animation (core/animation.h), from its checked local transform.
SceneNode restPose(const tg::Node& n, const glm::dmat4& local, const std::string& name,
                   int parent) {
  SceneNode out;
  out.name = name;
  out.parent = parent;
  out.hasMatrix = !n.matrix.empty();
  out.matrix = local;
  if (n.translation.size() == 3) out.translation = dvec3Or(n.translation, glm::dvec3(0.0));
  if (n.rotation.size() == 4)
    out.rotation =
        glm::normalize(glm::dquat(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]));
  if (n.scale.size() == 3) out.scale = dvec3Or(n.scale, glm::dvec3(1.0));
  return out;
}

// The indices [before, now) of what a node added to one of the scene's lists.
template <typename T>
std::vector<int> addedSince(size_t before, const std::vector<T>& list) {
  std::vector<int> out;
  for (size_t i = before; i < list.size(); ++i) out.push_back(int(i));
  return out;
}

glm::dmat4 placeNode(Loader& ld, int index, const glm::dmat4& parent, int parentNode) {
  if (!inRange(index, ld.model.nodes))
    ld.fail("node index " + std::to_string(index) + " out of range");
  const tg::Node& node = ld.model.nodes[size_t(index)];
  const std::string name = node.name.empty() ? "node#" + std::to_string(index) : node.name;
  const std::string where = "node " + named(name);
  // §3.5.3: the hierarchy is a set of disjoint trees; a second visit means a cycle or a
  // node with two parents, either of which would loop forever or multiply instances.
  if (ld.visited[size_t(index)])
    ld.fail(where + ": reached twice, the node hierarchy has a cycle or a shared child");
  ld.visited[size_t(index)] = true;
  const glm::dmat4 local = localTransform(ld, node, where);
  const glm::dmat4 world = parent * local;
  Scene& s = ld.scene;
  const size_t instances = s.instances.size(), lights = s.lights.size(), cameras = s.cameras.size();
  addMeshInstances(ld, node, world, where, name);
  addLight(ld, node, world, where);
  addCamera(ld, node, world, where);
  SceneNode placed = restPose(node, local, name, parentNode);
  placed.instances = addedSince(instances, s.instances);
  placed.lights = addedSince(lights, s.lights);
  placed.cameras = addedSince(cameras, s.cameras);
  ld.sceneNodeOf[size_t(index)] = int(s.nodes.size());
  s.nodes.push_back(std::move(placed));
  return world;
}

// Depth-first, parents before children, with an explicit stack: a file may nest nodes
// thousands deep, which recursion would turn into a stack overflow.
void placeTree(Loader& ld, int root) {
  struct Pending {
    int index;
    glm::dmat4 parent;
    int parentNode;  // in Scene::nodes
  };
  std::vector<Pending> pending = {{root, glm::dmat4(1.0), -1}};
  while (!pending.empty()) {
    const Pending p = pending.back();
    pending.pop_back();
    const glm::dmat4 world = placeNode(ld, p.index, p.parent, p.parentNode);
    const int placed = ld.sceneNodeOf[size_t(p.index)];
    const std::vector<int>& children = ld.model.nodes[size_t(p.index)].children;
    for (auto child = children.rbegin(); child != children.rend(); ++child)
      pending.push_back({*child, world, placed});
  }
}

// The default scene, else scene 0; a file without scenes shows every parentless node.
std::vector<int> rootNodes(const Loader& ld) {
  const tg::Model& m = ld.model;
  if (!m.scenes.empty()) {
    const int scene = m.defaultScene < 0 ? 0 : m.defaultScene;
    if (!inRange(scene, m.scenes))
      ld.fail("default scene index " + std::to_string(scene) + " out of range");
    return m.scenes[size_t(scene)].nodes;
  }
  std::vector<bool> isChild(m.nodes.size(), false);
  for (const tg::Node& node : m.nodes)
    for (int child : node.children)
      if (inRange(child, m.nodes)) isChild[size_t(child)] = true;
  std::vector<int> roots;
  for (size_t i = 0; i < m.nodes.size(); ++i)
    if (!isChild[i]) roots.push_back(int(i));
  return roots;
}

// What the file holds that photovr does not play: said in one line each, since the scene
// renders without it (in its bind pose, at time 0) and would otherwise look merely wrong.
void warnNotPlayed(Loader& ld, size_t weightChannels) {
  const tg::Model& m = ld.model;
  if (weightChannels > 0)
    ld.warn(std::to_string(weightChannels) +
            " animation channel(s) of morph target weights not played");
  size_t morphed = 0;
  for (const tg::Mesh& mesh : m.meshes)
    for (const tg::Primitive& prim : mesh.primitives) morphed += !prim.targets.empty();
  if (morphed > 0)
    ld.warn(std::to_string(morphed) +
            " primitive(s) with morph targets: targets not applied (base geometry)");
}

// ---------------------------------------------------------------------------------------
// Skins (glTF 2.0 §3.7.3; deformed by core/skinning.h)

glm::dmat4 inverseBindAt(const Loader& ld, const AccessorView& v, size_t joint,
                         const std::string& where) {
  glm::dmat4 m;
  for (int c = 0; c < 16; ++c) m[c / 4][c % 4] = componentAt(v, joint, c);  // column-major
  if (!isFinite(m)) ld.fail(where + ": non-finite inverse bind matrix " + std::to_string(joint));
  return m;
}

Skin readSkin(const Loader& ld, int index) {
  const tg::Skin& gs = ld.model.skins[size_t(index)];
  Skin skin;
  skin.name = gs.name.empty() ? "skin#" + std::to_string(index) : gs.name;
  const std::string where = "skin " + named(skin.name);
  if (gs.joints.empty()) ld.fail(where + ": has no joints");
  for (int j : gs.joints) {
    if (!inRange(j, ld.model.nodes) || ld.sceneNodeOf[size_t(j)] < 0)
      ld.fail(where + ": joint node " + std::to_string(j) + " is not in the scene");
    skin.joints.push_back(ld.sceneNodeOf[size_t(j)]);
  }
  skin.inverseBind.assign(skin.joints.size(), glm::dmat4(1.0));
  if (gs.inverseBindMatrices < 0) return skin;  // §3.7.3.1: identity matrices
  const std::string what = where + " inverseBindMatrices";
  const AccessorView v = viewAccessor(ld, gs.inverseBindMatrices, what);
  if (v.components != 16 || v.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
    ld.fail(what + ": must be float MAT4");
  if (v.count < skin.joints.size())
    ld.fail(what + ": " + std::to_string(v.count) + " matrices for " +
            std::to_string(skin.joints.size()) + " joints");
  for (size_t j = 0; j < skin.joints.size(); ++j)
    skin.inverseBind[j] = inverseBindAt(ld, v, j, what);
  return skin;
}

// The mesh's bind pose, kept for skinMesh; every weighted joint index names a joint.
void bindMesh(const Loader& ld, Mesh& mesh, int skin, size_t jointCount) {
  MeshSkinning& sk = mesh.skinning;
  for (size_t v = 0; v < sk.joints.size(); ++v)
    for (int k = 0; k < 4; ++k)
      if (sk.weights[v][k] > 0.0f && sk.joints[v][k] >= jointCount)
        ld.fail("mesh " + named(mesh.name) + " JOINTS_0: vertex " + std::to_string(v) +
                " names joint " + std::to_string(sk.joints[v][k]) + " of a skin with " +
                std::to_string(jointCount));
  sk.skin = skin;
  sk.positions = mesh.positions;
  sk.normals = mesh.normals;
  sk.tangents = mesh.tangents;
}

// Each skinned instance gets a mesh of its own (its vertices move with its skeleton) and an
// identity transform (§3.7.3.3: the skinned node's own transform is ignored; the joints
// carry the mesh, already re-based at Scene::origin).
void bindSkins(Loader& ld) {
  Scene& s = ld.scene;
  std::vector<int> skinOf(ld.model.skins.size(), -1);
  std::vector<int> users(s.meshes.size(), 0);
  for (const Instance& i : s.instances) ++users[size_t(i.mesh)];
  for (const Loader::SkinnedInstance& si : ld.skinnedInstances) {
    Instance& inst = s.instances[size_t(si.instance)];
    if (s.meshes[size_t(inst.mesh)].skinning.joints.empty()) {
      ld.warn("node " + named(inst.node) + ": skinned, but mesh " +
              named(s.meshes[size_t(inst.mesh)].name) + " has no JOINTS_0 (drawn rigid)");
      continue;
    }
    int& skin = skinOf[size_t(si.skin)];
    if (skin < 0) skin = int(s.skins.size()), s.skins.push_back(readSkin(ld, si.skin));
    if (users[size_t(inst.mesh)] > 1) {
      --users[size_t(inst.mesh)];
      Mesh own = s.meshes[size_t(inst.mesh)];
      inst.mesh = int(s.meshes.size());
      s.meshes.push_back(std::move(own));
    }
    bindMesh(ld, s.meshes[size_t(inst.mesh)], skin, s.skins[size_t(skin)].joints.size());
    inst.transform = inst.previousTransform = glm::mat4(1.0f);
  }
}

// ---------------------------------------------------------------------------------------
// Animations (glTF 2.0 §3.11; played by core/animation.h)

Interpolation interpolationOf(const Loader& ld, const std::string& name, const std::string& where) {
  if (name.empty() || name == "LINEAR") return Interpolation::Linear;
  if (name == "STEP") return Interpolation::Step;
  if (name == "CUBICSPLINE") return Interpolation::CubicSpline;
  ld.fail(where + ": unknown interpolation '" + name + "'");
}

// §3.11: key times are scalar floats, strictly increasing; each key holds one value, or
// three (in-tangent, value, out-tangent) for a cubic spline.
void readSampler(const Loader& ld, const tg::AnimationSampler& sampler, AnimationChannel& c,
                 const std::string& where) {
  c.interpolation = interpolationOf(ld, sampler.interpolation, where);
  for (const glm::vec1& t : readVectors<1>(ld, sampler.input, where + " input"))
    c.times.push_back(t.x);
  for (size_t k = 0; k < c.times.size(); ++k)
    if (!std::isfinite(c.times[k]) || (k > 0 && !(c.times[k] > c.times[k - 1])))
      ld.fail(where + ": key times must be finite and strictly increasing");
  if (c.path == AnimationPath::Rotation) {
    for (const glm::vec4& v : readVectors<4>(ld, sampler.output, where + " output"))
      c.values.push_back(v);
  } else {
    for (const glm::vec3& v : readVectors<3>(ld, sampler.output, where + " output"))
      c.values.emplace_back(v, 0.0f);
  }
  const size_t perKey = c.interpolation == Interpolation::CubicSpline ? 3 : 1;
  if (c.times.empty() || c.values.size() != perKey * c.times.size())
    ld.fail(where + ": " + std::to_string(c.values.size()) + " output values for " +
            std::to_string(c.times.size()) + " key times (expected " + std::to_string(perKey) +
            " per key, at least one key)");
  for (const glm::vec4& v : c.values)
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z) || !std::isfinite(v.w))
      ld.fail(where + ": non-finite output value");
}

// One channel, or none when it targets what photovr does not animate (counted: weights).
void readChannel(Loader& ld, const tg::Animation& a, const tg::AnimationChannel& ch, Animation& out,
                 size_t& weightChannels, const std::string& where) {
  if (ch.target_path == "weights") {
    ++weightChannels;
    return;
  }
  const std::map<std::string, AnimationPath> paths = {{"translation", AnimationPath::Translation},
                                                      {"rotation", AnimationPath::Rotation},
                                                      {"scale", AnimationPath::Scale}};
  const auto path = paths.find(ch.target_path);
  if (path == paths.end()) ld.fail(where + ": unknown target path '" + ch.target_path + "'");
  if (!inRange(ch.target_node, ld.model.nodes))
    ld.fail(where + ": target node " + std::to_string(ch.target_node) + " out of range");
  const int node = ld.sceneNodeOf[size_t(ch.target_node)];
  if (node < 0) return;  // a node of another scene
  if (ld.scene.nodes[size_t(node)].hasMatrix)
    ld.fail(where + ": targets node '" + ld.scene.nodes[size_t(node)].name +
            "', which has a matrix (§3.11: animated nodes have TRS only)");
  if (!inRange(ch.sampler, a.samplers))
    ld.fail(where + ": sampler " + std::to_string(ch.sampler) + " out of range");
  AnimationChannel c;
  c.node = node;
  c.path = path->second;
  readSampler(ld, a.samplers[size_t(ch.sampler)], c, where);
  out.channels.push_back(std::move(c));
}

void readAnimations(Loader& ld) {
  size_t weightChannels = 0;
  for (size_t i = 0; i < ld.model.animations.size(); ++i) {
    const tg::Animation& a = ld.model.animations[i];
    Animation out;
    out.name = a.name.empty() ? "animation#" + std::to_string(i) : a.name;
    for (size_t k = 0; k < a.channels.size(); ++k)
      readChannel(ld, a, a.channels[k], out, weightChannels,
                  "animation " + named(out.name) + " channel " + std::to_string(k));
    if (!out.channels.empty()) ld.scene.animations.push_back(std::move(out));
  }
  warnNotPlayed(ld, weightChannels);
}

}  // namespace

Scene loadGltf(const std::string& path) {
  const std::vector<uint8_t> bytes = readFile(path);
  std::vector<std::string> warnings;
  const tg::Model model = parseModel(path, bytes, warnings);
  std::vector<Scene::Extension> extensions;
  checkExtensions(model, path, warnings, extensions);
  checkBufferViews(model, path);
  Loader ld(path, model);
  ld.scene.name = path;
  ld.scene.warnings = std::move(warnings);
  ld.scene.extensions = std::move(extensions);
  for (size_t i = 0; i < model.materials.size(); ++i)
    ld.scene.materials.push_back(convertMaterial(ld, model.materials[i], i));
  for (int root : rootNodes(ld)) placeTree(ld, root);
  if (ld.scene.meshes.empty()) ld.fail("contains no triangle meshes");
  readAnimations(ld);
  // Finite transforms can still carry vertices past float range (a matrix of 1e38s):
  // every later stage would see infinities.
  if (!storePlacement(ld.scene, ld.placed))
    ld.fail("the node transforms take the geometry beyond float range (non-finite bounds)");
  bindSkins(ld);
  skinRestPose(ld.scene);
  const Bounds world = ld.scene.worldBounds();
  const auto finite = [](const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
  };
  if (!finite(world.min) || !finite(world.max))
    ld.fail("the node transforms take the geometry beyond float range (non-finite bounds)");
  return std::move(ld.scene);
}

}  // namespace photovr
