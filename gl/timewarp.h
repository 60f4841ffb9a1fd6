// The headset's compositor in one compute pass (issue 6, item 5): depth-based re-projection
// of each eye's last rendered colour + depth (pose A) to the newest pose (B) by an iterative
// backward search per output pixel, the DK2 lens with per-channel chromatic correction,
// exposure, PBR Neutral, sRGB and the panel's rotation, straight into a PanelOutput's RGBA8
// texture. shaders/timewarp.comp documents the search.
//
// Against the grid re-projection (gl/compositor.h Reprojector) followed by the Distorter
// and the PanelOutput, which stay as the reference implementation the tests compare with:
// one pass instead of three, no intermediate panel, every invocation independent (llvmpipe
// runs compute on all cores, the grid's vertex stage on one), and only the pixels the lens
// shows are warped. Per pixel it costs one depth fetch under pure rotation and one per
// march step (params.stepPixels) of parallax.
//
// Limits: the search runs between the nearest and farthest depth within one 16-pixel tile
// of the rotation-only point (and on to infinity); parallax beyond ~16 pixels per refresh (a head
// moving ~4 cm past a surface 0.5 m away at a DK2 eye buffer) can miss a near surface's edge. The
// eye mode (runEyes) writes pose B's eye buffers for tests and eye images.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "core/camera.h"
#include "gl/compositor.h"
#include "gl/panel_output.h"
#include "gl/pass_list.h"
#include "gl/program.h"

namespace photovr::gl {

struct TimewarpParams {
  float depthRatio = 0.05f;  // A's depth jumping nearer by more than this: a silhouette
  float stepPixels = 1.0f;   // march step along the ray's segment in A's image
  int maxSteps = 32;         // longer segments take longer steps
};

// Timewarp's entry points, each one PassList (passes()).
enum class TimewarpRun { Panel, PanelAsRendered, PanelFloor, Eyes };

class Timewarp {
 public:
  // eyeWidth x eyeHeight eye buffers rendered with eyeFov[eye] (pose A's and B's), shown
  // through 'lens' on its panel.
  Timewarp(const LensParams& lens, int eyeWidth, int eyeHeight,
           const std::array<FovTangents, 2>& eyeFov, const TimewarpParams& params = {});
  ~Timewarp();
  Timewarp(const Timewarp&) = delete;
  Timewarp& operator=(const Timewarp&) = delete;

  // Both eyes of 'colorArray'/'depthArray' (2-layer: float RGB(A), reversed-Z R32F or D32F)
  // rendered with 'from' (zfar 0), shown at 'to', into out.texture(). 'out' must be this
  // lens's panel size.
  void runPanel(unsigned colorArray, unsigned depthArray, const std::array<EyeCamera, 2>& from,
                const std::array<EyeCamera, 2>& to, float exposure, PanelOutput& out);
  // The frame as rendered at 'at', no re-projection: the lens, the chromatic samples and
  // the display transform only (the frame's depth is not read). Between the colour taps
  // across a silhouette it blends, as the distortion chain does.
  void runPanelAsRendered(unsigned colorArray, const std::array<EyeCamera, 2>& at, float exposure,
                          PanelOutput& out);
  // A measurement, never shown (bench_compositor): the least any depth re-projecting lens
  // pass does per pixel the lens shows (shaders/timewarp_floor.comp), timed to bound what
  // this machine's GL can reach.
  void runPanelFloor(unsigned colorArray, unsigned depthArray, const std::array<EyeCamera, 2>& at,
                     PanelOutput& out);
  // Pose B's eye buffers instead of the panel (eyes [0, eyeCount)).
  void runEyes(unsigned colorArray, unsigned depthArray, const std::array<EyeCamera, 2>& from,
               const std::array<EyeCamera, 2>& to, int eyeCount = 2);

  std::vector<glm::vec4> readColor(int eye) const;  // of runEyes; alpha = origin (compositor.h)
  std::vector<float> readDepth(int eye) const;      // of runEyes; reversed-Z at B
  // Origins of the last run's outputs: eye pixels (runEyes) or lens-visible panel pixels.
  ReprojectStats stats(int eye) const;

  void setParams(const TimewarpParams& p) { params_ = p; }
  // The tangents the panel shows per eye (overscan: the lens's field, inside the eye buffers'
  // FOV); directions beyond are shown as the field's edge. Default: the eye buffer's FOV.
  void setShownField(const std::array<FovTangents, 2>& field) { field_ = field; }
  int eyeWidth() const { return eyeWidth_; }
  int eyeHeight() const { return eyeHeight_; }
  // The passes of each entry point, in order, with what they read and write (textures and
  // buffers by name; the lens table and groups are made before, the uniforms by each run).
  const PassList& passes(TimewarpRun run) const { return passes_[size_t(run)]; }

 private:
  struct FrameIn {  // the running entry point's arguments, for the passes
    unsigned color = 0, depth = 0;
    PanelOutput* out = nullptr;
    int eyeCount = 2;
  };
  void buildPasses();
  PassDecl tilePass(int pass);
  PassDecl panelPass(TimewarpRun run);
  PassDecl eyePass();
  void setUniforms(const std::array<EyeCamera, 2>& from, const std::array<EyeCamera, 2>& to,
                   int eyeCount, float exposure, int rotation);
  void checkSearch(const std::array<EyeCamera, 2>& from, int eyeCount) const;
  void runTiles(int pass);
  void bindSearch(unsigned depthArray);
  void bindColor(unsigned colorArray);
  void checkPanel(const PanelOutput& out);
  void drawPanel(const Program& program, PanelOutput& out);
  void drawEyes(int eyeCount);
  void unbindSamplers();
  void buildLensTable(const LensParams& lens, const std::array<FovTangents, 2>& eyeFov);
  // The list of output groups (COMP_TW_GROUP squared texels) showing a pixel the lens sees,
  // for out's rotation: the panel pass computes those and clears the rest.
  void buildLensGroups(const PanelOutput& out);
  bool groupSees(int rotation, int outWidth, int outHeight, int gx, int gy) const;

  int eyeWidth_, eyeHeight_, panelWidth_, panelHeight_;
  glm::ivec2 tiles_;
  TimewarpParams params_;
  std::optional<std::array<FovTangents, 2>> field_;  // setShownField
  Program panelProgram_, asRenderedProgram_, eyeProgram_, tileProgram_;
  std::unique_ptr<Program> floorProgram_;  // runPanelFloor's, made on its first use
  unsigned uniforms_ = 0, stats_ = 0, linearSampler_ = 0;
  std::vector<bool> lensSees_;        // per landscape panel texel, as stored
  std::array<int, 2> lensVisible_{};  // panel pixels each eye's lens shows
  unsigned lensGroups_ = 0;           // SSBO of buildLensGroups' list
  int lensGroupCount_ = 0, lensGroupRotation_ = -1;
  std::array<int, 2> counted_{};  // outputs the last run sorted by origin, per eye
  unsigned lensTable_ = 0, tileRange_ = 0, tileBound_ = 0, eyeColor_ = 0, eyeDepth_ = 0;
  FrameIn frameIn_;
  std::array<PassList, 4> passes_;  // by TimewarpRun
};

}  // namespace photovr::gl
