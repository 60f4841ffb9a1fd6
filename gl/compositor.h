// Headset compositor passes (issue 6, item 5): depth-based re-projection of each eye's last
// rendered colour + depth to a newer pose, and the DK2 lens distortion pass with chromatic
// correction. Both eyes live in 2-layer array textures, layer = eye.
//
// The headset itself runs gl/timewarp.h, which does both (and the panel output) in one
// pass. These are the reference implementation it is tested against and the bench's
// baseline: the forward warp is exact where the search is approximate, and the Distorter's
// debug run records the footprint the hidden-area mask is checked with.
//
// Re-projection (Reprojector) is a forward warp of a depth-displaced grid mesh (dk2.md §7):
// one vertex per pose-A pixel sample (plus a border ring), z-buffered (reversed-Z, GL_GEQUAL)
// and rasterised at pose B; each fragment takes A's colour bilinearly at its interpolated A
// texel, which is exact on planar surfaces. Triangles that both span a depth discontinuity
// (far / near distance > 1 + depthRatio) and grow by more than areaRatio in B are
// disocclusions: drawn flat with the colour of their farthest vertex, at half that vertex's
// reversed-Z depth, so every real surface drawn there wins and holes take the background.
// Pixels outside A's frustum stay uncovered (alpha 0). Output alpha marks the origin:
// 1 re-projected, 0.5 disocclusion fill, 0 uncovered.
//
// Distortion (Distorter): per display pixel of each eye's half of the panel and per colour
// channel, the tan-angle of hmd::screenToTan (LibOVR CatmullRom10 + chromatic terms, float),
// a bilinear sample of the eye buffer there, black where the lens does not see. gl/ does not
// depend on hmd/: the lens arrives flattened in LensParams (hmd::flattenLens fills it).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/camera.h"
#include "core/lens_params.h"
#include "gl/program.h"

namespace photovr::gl {

struct ReprojectParams {
  float depthRatio = 0.05f;     // far / near distance above 1 + this: depth discontinuity
  float areaRatio = 2.0f;       // B area / A area above this: the triangle is stretched
  float fillDepthScale = 0.5f;  // fill fragments' depth = this x their far vertex's depth
  // One grid vertex every gridStep pixels of A. 1 is exact everywhere but costs a vertex
  // per pixel, and llvmpipe shades vertices on one thread (bench_compositor measures it);
  // 2-4 stay exact on planar surfaces and only coarsen depth edges.
  int gridStep = 1;
};

struct ReprojectStats {
  int reprojected = 0, filled = 0, uncovered = 0;
  double disoccludedFraction() const {  // filled + uncovered over all pixels
    const int n = reprojected + filled + uncovered;
    return n ? double(filled + uncovered) / n : 0.0;
  }
};

class Reprojector {
 public:
  Reprojector(int width, int height, const ReprojectParams& params = {});
  ~Reprojector();
  Reprojector(const Reprojector&) = delete;
  Reprojector& operator=(const Reprojector&) = delete;

  // CPU input of one eye into the owned inputs (RGBA32F colour, R32F reversed-Z depth),
  // rows bottom-up, width x height.
  void upload(int eye, const glm::vec4* color, const float* depth);
  // Re-projects eyes [0, eyeCount) rendered with cameras 'from' (pose A: pose, FOV, znear,
  // jitter; zfar must be 0, infinite reversed-Z) to cameras 'to' (pose B; its projection(),
  // jitter included). The first form reads the uploaded inputs; the second any 2-layer
  // arrays (colour: float RGB(A); depth: R32F or D32F) of this size, e.g. the denoiser's.
  void run(const std::array<EyeCamera, 2>& from, const std::array<EyeCamera, 2>& to,
           int eyeCount = 2);
  void run(unsigned colorArray, unsigned depthArray, const std::array<EyeCamera, 2>& from,
           const std::array<EyeCamera, 2>& to, int eyeCount = 2);

  unsigned colorTexture() const { return color_; }         // RGBA16F, alpha = origin (see above)
  unsigned inputColorTexture() const { return inColor_; }  // what upload() filled
  unsigned inputDepthTexture() const { return inDepth_; }
  unsigned depthTexture() const { return depth_; }  // D32F reversed-Z at pose B
  std::vector<glm::vec4> readColor(int eye) const;
  std::vector<float> readDepth(int eye) const;
  ReprojectStats stats(int eye) const;  // from readColor's alpha

  void setParams(const ReprojectParams& p) { params_ = p; }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  int width_, height_;
  ReprojectParams params_;
  Program program_;
  unsigned uniforms_ = 0, vao_ = 0, fbo_ = 0;
  unsigned inColor_ = 0, inDepth_ = 0, color_ = 0, depth_ = 0;
};

// The lens arrives from hmd::flattenLens (core/lens_params.h). Named here too, as gl::LensParams,
// for the callers that spelled it so when it lived in this header.
using photovr::LensParams;

namespace shared {
struct DistortUniforms;
}

// The distortion shaders' uniforms for one eye (shaders/compositor_shared.h); 'footprint'
// asks distort.comp for its debug outputs.
shared::DistortUniforms distortUniforms(const LensParams& lens, int eye, const FovTangents& fov,
                                        int eyeWidth, int eyeHeight, bool footprint);

// One panel pixel's debug record: the tan-angle each channel samples, and whether the
// lens sees the pixel.
struct DistortSample {
  glm::vec2 tan[3];
  bool sees;
};

class Distorter {
 public:
  // eyeWidth x eyeHeight eye buffers rendered with eyeFov[eye].
  Distorter(const LensParams& lens, int eyeWidth, int eyeHeight,
            const std::array<FovTangents, 2>& eyeFov);
  ~Distorter();
  Distorter(const Distorter&) = delete;
  Distorter& operator=(const Distorter&) = delete;

  // Distorts eyes [0, eyeCount) of a 2-layer float array (linear colour) onto the panel;
  // with 'footprint' (a debug run) also records which eye-buffer texels were read (cleared
  // first) and each pixel's tan-angles for readSamples(). Without it only the panel is
  // written: the two RGBA32F debug images would double the pass's memory traffic.
  void run(unsigned eyeArray, int eyeCount = 2, bool footprint = false);

  unsigned panelTexture() const { return panel_; }  // RGBA16F, hResolution x vResolution
  int panelWidth() const { return lens_.hResolution; }
  int panelHeight() const { return lens_.vResolution; }
  std::vector<glm::vec4> readPanel() const;           // rows bottom-up
  std::vector<DistortSample> readSamples() const;     // panel-sized; of the last debug run
  std::vector<uint8_t> readFootprint(int eye) const;  // eye-buffer sized, 1 = read

  // The lens's derived values, as hmd::flattenLens stored them.
  glm::vec2 lensCentre(int eye) const { return lens_.lensCentre[size_t(eye)]; }
  glm::vec2 screenToLensScale() const { return lens_.screenToLensScale; }

 private:
  LensParams lens_;
  int eyeWidth_, eyeHeight_;
  std::array<FovTangents, 2> fov_;
  Program program_;
  unsigned uniforms_ = 0, linearSampler_ = 0;
  unsigned panel_ = 0, tanRG_ = 0, tanB_ = 0, footprint_ = 0;
};

}  // namespace photovr::gl
