// The stereo-instanced G-buffer pass. Both eyes go into 2-layer array textures in ONE
// instanced draw per mesh. Reads: SceneGpu (meshes, instances, materials, textures),
// both EyeCameras. Writes (per layer = eye):
//   visibility RGBA32UI  instance, triangle, floatBits(b1), floatBits(b2)
//   normal     RGBA16F   world shading normal (normal-mapped, facing the viewer side)
//   baseColor  RGBA16F   linear base colour, a = occlusion
//   material   RGBA16F   metallic, roughness
//   emission   RGBA16F   linear emitted radiance
//   motion     RG16F     pixels to the same surface point in the previous frame
//   depth      D32F      reversed-Z (near 1, far 0), GL_ZERO_TO_ONE clip control
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/camera.h"
#include "core/visibility.h"
#include "gl/program.h"
#include "gl/scene_gpu.h"

namespace photovr::gl {

enum class GBufferTarget { Visibility, Normal, BaseColor, Material, Emission, Motion, Count };

// One eye's G-buffer on the CPU, rows bottom-up as GL stores them (row 0 = lowest).
struct GBufferImage {
  int width = 0, height = 0;
  std::vector<glm::uvec4> visibility;
  std::vector<glm::vec4> normal, baseColor, material, emission;
  std::vector<glm::vec2> motion;
  std::vector<float> depth;
  size_t index(int x, int y) const { return size_t(y) * width + x; }
  // Empties every target but the visibility record (their storage kept for the next read).
  void clearAllButVisibility() {
    normal.clear(), baseColor.clear(), material.clear(), emission.clear();
    motion.clear(), depth.clear();
  }
  // Pixel i's visibility target as a record (instance kNoHitInstance: the background).
  VisibilityRecord record(size_t i) const {
    const glm::uvec4 v = visibility[i];
    return {v.x, v.y, glm::uintBitsToFloat(v.z), glm::uintBitsToFloat(v.w)};
  }
};

// What a read-back copies to the CPU: every target (the G-buffer mode's images, tests), or
// the visibility record alone, which is all the hybrid tracer reads (it rebuilds each hit
// from the record; the denoiser reads the other targets on the GPU). The record is 16 of
// the 84 bytes a pixel has across the targets, and needs no conversion from half floats.
enum class GBufferRead { All, Visibility };

enum class EyeRouting {
  Layered,     // gl_Layer from the vertex shader (GL_ARB_shader_viewport_layer_array)
  SideBySide,  // one double-width target, eyes in halves clipped by gl_ClipDistance
};

class GBufferPass {
 public:
  // Layered unless the current context lacks GL_ARB_shader_viewport_layer_array (then
  // SideBySide); 'routing' SideBySide forces the fallback.
  GBufferPass(int eyeWidth, int eyeHeight, EyeRouting routing = EyeRouting::Layered);
  ~GBufferPass();
  GBufferPass(const GBufferPass&) = delete;
  GBufferPass& operator=(const GBufferPass&) = delete;

  // previousViewProjection: last frame's unjittered view-projection per eye (for motion);
  // pass the current one for a first frame.
  void render(const SceneGpu& scene, const std::array<EyeCamera, 2>& eyes,
              const std::array<glm::mat4, 2>& previousViewProjection);
  GBufferImage read(int eye) const;
  // Into 'img', reusing its vectors' storage: fresh memory costs its first touch, ~3 us per
  // 4 KiB page in the VM measured here, ~45 ms per 960x1080 RGBA32F target (docs/
  // ARCHITECTURE.md, "Memory reuse"); a sequence reads into the same image every frame.
  void read(int eye, GBufferImage& img, GBufferRead what = GBufferRead::All) const;
  void finish() const;  // waits until the G-buffer is complete (for timing stages apart)

  EyeRouting routing() const { return routing_; }
  int width() const { return width_; }
  int height() const { return height_; }
  unsigned texture(GBufferTarget t) const { return layers_[int(t)]; }
  unsigned depthTexture() const { return depthLayers_; }

 private:
  void createTargets();
  void uploadFrame(const std::array<EyeCamera, 2>& eyes,
                   const std::array<glm::mat4, 2>& previousViewProjection);
  void drawMeshes(const SceneGpu& scene);
  void copySideBySideToLayers();

  int width_, height_;
  EyeRouting routing_;
  Program program_;
  unsigned frameBuffer_ = 0;  // UBO with FrameUniforms
  unsigned fbo_ = 0;
  unsigned layers_[int(GBufferTarget::Count)] = {};  // 2-layer arrays (what consumers read)
  unsigned depthLayers_ = 0;
  unsigned wide_[int(GBufferTarget::Count)] = {};  // side-by-side targets (fallback only)
  unsigned wideDepth_ = 0;
};

}  // namespace photovr::gl
