#include "gl/scene_gpu.h"

#include <algorithm>
#include <cmath>

#include "gl/gl_api.h"
#include "shaders/gbuffer_shared.h"

namespace photovr::gl {
namespace {

static_assert(sizeof(shared::GpuInstance) == 208, "std430 layout of GpuInstance");
static_assert(sizeof(shared::GpuMaterial) == 256, "GpuMaterial: 256-byte uniform-range stride");

template <typename T>
GLuint makeBuffer(const std::vector<T>& data) {
  GLuint b = 0;
  api::CreateBuffers(1, &b);
  // Zero-sized storage is an error in GL; a 16-byte dummy keeps absent attributes simple.
  const size_t bytes = std::max<size_t>(data.size() * sizeof(T), 16);
  api::NamedBufferStorage(b, GLsizeiptr(bytes), nullptr, GL_DYNAMIC_STORAGE_BIT);
  if (!data.empty())
    api::NamedBufferSubData(b, 0, GLsizeiptr(data.size() * sizeof(T)), data.data());
  return b;
}

void attribute(GLuint vao, GLuint location, GLuint buffer, int components, size_t stride,
               bool present) {
  if (!present) return;  // disabled attributes read the default (0, 0, 0, 1)
  api::VertexArrayVertexBuffer(vao, location, buffer, 0, GLsizei(stride));
  api::EnableVertexArrayAttrib(vao, location);
  api::VertexArrayAttribFormat(vao, location, components, GL_FLOAT, GL_FALSE, 0);
  api::VertexArrayAttribBinding(vao, location, location);
}

GLint wrapMode(Texture::Wrap w) {
  switch (w) {
    case Texture::Wrap::Clamp:
      return GL_CLAMP_TO_EDGE;
    case Texture::Wrap::Mirror:
      return GL_MIRRORED_REPEAT;
    default:
      return GL_REPEAT;
  }
}

// A skinned mesh's previous pose; its current one until it has been posed.
const std::vector<glm::vec3>& previousPositions(const Mesh& mesh) {
  const std::vector<glm::vec3>& p = mesh.skinning.previousPositions;
  return p.size() == mesh.positions.size() ? p : mesh.positions;
}

shared::GpuInstance gpuInstance(const Instance& inst, uint32_t sceneIndex) {
  shared::GpuInstance g{};
  g.model = inst.transform;
  g.previousModel = inst.previousTransform;
  g.normalModel = glm::mat4(glm::transpose(glm::inverse(glm::mat3(inst.transform))));
  g.info = glm::uvec4(sceneIndex, glm::determinant(glm::mat3(inst.transform)) < 0.0f, 0, 0);
  return g;
}

}  // namespace

SceneGpu::SceneGpu(const Scene& scene) {
  for (const Mesh& m : scene.meshes) uploadMesh(m);
  // Group instances by mesh: GPU slot order is mesh-major, stable within a mesh.
  std::vector<std::vector<uint32_t>> byMesh(scene.meshes.size());
  for (uint32_t i = 0; i < scene.instances.size(); ++i)
    byMesh[scene.instances[i].mesh].push_back(i);
  for (size_t m = 0; m < byMesh.size(); ++m) {
    meshes_[m].firstInstance = uint32_t(gpuOrder_.size());
    meshes_[m].instanceCount = uint32_t(byMesh[m].size());
    gpuOrder_.insert(gpuOrder_.end(), byMesh[m].begin(), byMesh[m].end());
    for (uint32_t i : byMesh[m])
      meshes_[m].anyMirrored |= glm::determinant(glm::mat3(scene.instances[i].transform)) < 0.0f;
  }
  instanceBuffer_ =
      makeBuffer(std::vector<shared::GpuInstance>(std::max<size_t>(gpuOrder_.size(), 1)));
  updateInstances(scene);
  uploadMaterials(scene);
}

SceneGpu::~SceneGpu() {
  for (GpuMesh& m : meshes_) {
    api::DeleteVertexArrays(1, &m.vao);
    api::DeleteBuffers(7, m.buffers);
  }
  api::DeleteBuffers(1, &instanceBuffer_);
  api::DeleteBuffers(1, &materialBuffer_);
  for (auto& [key, tex] : textures_) api::DeleteTextures(1, &tex);
}

void SceneGpu::uploadMesh(const Mesh& mesh) {
  GpuMesh g;
  g.buffers[0] = makeBuffer(mesh.positions);
  g.buffers[1] = makeBuffer(mesh.normals);
  g.buffers[2] = makeBuffer(mesh.tangents);
  g.buffers[3] = makeBuffer(mesh.uv0);
  g.buffers[4] = makeBuffer(mesh.uv1);
  g.buffers[5] = makeBuffer(mesh.indices);
  g.indexCount = uint32_t(mesh.indices.size());
  g.material = mesh.material;
  api::CreateVertexArrays(1, &g.vao);
  attribute(g.vao, 0, g.buffers[0], 3, sizeof(glm::vec3), true);
  if (mesh.skinned()) g.buffers[6] = makeBuffer(previousPositions(mesh));
  attribute(g.vao, 5, mesh.skinned() ? g.buffers[6] : g.buffers[0], 3, sizeof(glm::vec3), true);
  attribute(g.vao, 1, g.buffers[1], 3, sizeof(glm::vec3), !mesh.normals.empty());
  attribute(g.vao, 2, g.buffers[2], 4, sizeof(glm::vec4), !mesh.tangents.empty());
  attribute(g.vao, 3, g.buffers[3], 2, sizeof(glm::vec2), !mesh.uv0.empty());
  attribute(g.vao, 4, g.buffers[4], 2, sizeof(glm::vec2), !mesh.uv1.empty());
  api::VertexArrayElementBuffer(g.vao, g.buffers[5]);
  meshes_.push_back(g);
}

void SceneGpu::updateInstances(const Scene& scene) {
  std::vector<shared::GpuInstance> data;
  data.reserve(gpuOrder_.size());
  for (uint32_t sceneIndex : gpuOrder_)
    data.push_back(gpuInstance(scene.instances[sceneIndex], sceneIndex));
  if (!data.empty())
    api::NamedBufferSubData(instanceBuffer_, 0, GLsizeiptr(data.size() * sizeof(data[0])),
                            data.data());
}

template <typename T>
void replaceData(GLuint buffer, const std::vector<T>& data) {
  if (!data.empty())
    api::NamedBufferSubData(buffer, 0, GLsizeiptr(data.size() * sizeof(T)), data.data());
}

void SceneGpu::updateMeshVertices(const Scene& scene, const std::vector<int>& meshes) {
  for (int m : meshes) {
    const Mesh& mesh = scene.meshes[size_t(m)];
    replaceData(meshes_[size_t(m)].buffers[0], mesh.positions);
    replaceData(meshes_[size_t(m)].buffers[1], mesh.normals);
    replaceData(meshes_[size_t(m)].buffers[2], mesh.tangents);
    replaceData(meshes_[size_t(m)].buffers[6], previousPositions(mesh));
  }
}

unsigned SceneGpu::textureFor(const Scene& scene, const TextureRef& ref, bool srgb) {
  if (!ref.valid() || ref.texture >= int(scene.textures.size())) return 0;
  auto [it, inserted] = textures_.try_emplace({ref.texture, srgb}, 0u);
  if (!inserted) return it->second;
  const Texture& t = scene.textures[ref.texture];
  const int levels = 1 + int(std::floor(std::log2(std::max(t.width, t.height))));
  GLuint tex = 0;
  api::CreateTextures(GL_TEXTURE_2D, 1, &tex);
  api::TextureStorage2D(tex, levels, srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, t.width, t.height);
  api::PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  // Texture rows are stored top row first, as glTF's uv (0, 0) is the top-left corner:
  // uploading row 0 at GL's t = 0 makes texture(uv) match glTF's convention directly.
  api::TextureSubImage2D(tex, 0, 0, 0, t.width, t.height, GL_RGBA, GL_UNSIGNED_BYTE, t.rgba.data());
  api::GenerateTextureMipmap(tex);
  api::TextureParameteri(tex, GL_TEXTURE_WRAP_S, wrapMode(t.wrapS));
  api::TextureParameteri(tex, GL_TEXTURE_WRAP_T, wrapMode(t.wrapT));
  api::TextureParameteri(tex, GL_TEXTURE_MAG_FILTER, t.nearest ? GL_NEAREST : GL_LINEAR);
  api::TextureParameteri(tex, GL_TEXTURE_MIN_FILTER,
                         t.nearest ? GL_NEAREST_MIPMAP_NEAREST : GL_LINEAR_MIPMAP_LINEAR);
  it->second = tex;
  return tex;
}

void SceneGpu::uploadMaterials(const Scene& scene) {
  std::vector<shared::GpuMaterial> data;
  for (size_t m = 0; m < scene.materials.size(); ++m) {
    const Material& mat = scene.materials[m];
    shared::GpuMaterial g{};
    g.baseColorFactor = mat.baseColorFactor;
    // Unlit: the emission output is the base colour (its factor and texture in the slot).
    g.emissive =
        glm::vec4(mat.unlit ? glm::vec3(mat.baseColorFactor) : mat.emission(), mat.alphaCutoff);
    g.params =
        glm::vec4(mat.metallicFactor, mat.roughnessFactor, mat.normalScale, mat.occlusionStrength);
    const unsigned alpha = mat.alphaMode == AlphaMode::Mask    ? ALPHA_MASK
                           : mat.alphaMode == AlphaMode::Blend ? ALPHA_BLEND
                                                               : ALPHA_OPAQUE;
    g.flags = glm::uvec4(alpha, mat.cullsBackFaces() ? 0u : 1u, 0u, 0u);
    const TextureRef* refs[SLOT_COUNT] = {&mat.baseColorTexture, &mat.metallicRoughnessTexture,
                                          &mat.normalTexture, &mat.occlusionTexture,
                                          mat.unlit ? &mat.baseColorTexture : &mat.emissiveTexture};
    for (int s = 0; s < SLOT_COUNT; ++s) {
      const bool srgb = s == SLOT_BASE_COLOR || s == SLOT_EMISSIVE;
      const unsigned tex = textureFor(scene, *refs[s], srgb);
      slotTextures_.push_back(tex);
      if (tex) g.flags.z |= 1u << s;
      if (refs[s]->texCoord == 1) g.flags.w |= 1u << s;
      const glm::mat3 t = refs[s]->transform.matrix();
      g.uvTransform[2 * s] = glm::vec4(t[0][0], t[1][0], t[2][0], 0.0f);
      g.uvTransform[2 * s + 1] = glm::vec4(t[0][1], t[1][1], t[2][1], 0.0f);
    }
    doubleSided_.push_back(!mat.cullsBackFaces());
    data.push_back(g);
  }
  if (data.empty()) data.emplace_back();
  materialBuffer_ = makeBuffer(data);
}

}  // namespace photovr::gl
