// A Scene's meshes, textures, materials and instances in GL buffers, ready for the
// stereo-instanced G-buffer: the instances of each mesh are stored contiguously so one
// instanced draw covers them all.
#pragma once

#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "core/scene.h"

namespace photovr::gl {

struct GpuMesh {
  unsigned vao = 0;
  // position, normal, tangent, uv0, uv1, index, previous position (skinned meshes only;
  // the others read their positions there too)
  unsigned buffers[7] = {};
  uint32_t indexCount = 0;
  int material = 0;
  uint32_t firstInstance = 0;  // into the instance buffer
  uint32_t instanceCount = 0;
  bool anyMirrored = false;  // some instance has a negative determinant (flips winding)
};

class SceneGpu {
 public:
  explicit SceneGpu(const Scene& scene);
  ~SceneGpu();
  SceneGpu(const SceneGpu&) = delete;
  SceneGpu& operator=(const SceneGpu&) = delete;

  // Re-uploads instance transforms (and their previous-frame transforms).
  void updateInstances(const Scene& scene);
  // Re-uploads these meshes' positions, normals and tangents (skinned meshes, posed).
  void updateMeshVertices(const Scene& scene, const std::vector<int>& meshes);

  const std::vector<GpuMesh>& meshes() const { return meshes_; }
  unsigned instanceBuffer() const { return instanceBuffer_; }
  unsigned materialBuffer() const { return materialBuffer_; }
  // GL texture of a material slot, 0 if the slot is empty.
  unsigned texture(int material, int slot) const { return slotTextures_[material * 5 + slot]; }
  bool cullBackFaces(int material) const { return !doubleSided_[material]; }

 private:
  void uploadMesh(const Mesh& mesh);
  void uploadMaterials(const Scene& scene);
  unsigned textureFor(const Scene& scene, const TextureRef& ref, bool srgb);

  std::vector<GpuMesh> meshes_;
  std::vector<uint32_t> gpuOrder_;  // scene instance index of each GPU instance slot
  unsigned instanceBuffer_ = 0;
  unsigned materialBuffer_ = 0;
  std::map<std::pair<int, bool>, unsigned> textures_;  // (texture, sRGB) -> GL texture
  std::vector<unsigned> slotTextures_;
  std::vector<bool> doubleSided_;
};

}  // namespace photovr::gl
