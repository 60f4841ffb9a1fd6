// Issue 5's temporal claims on the Cornell box, one 48x54 eye, 1 spp per frame:
// - after 32 frames of slow camera motion the denoised error stays within 2x of the
//   static-camera error (history follows the motion vectors);
// - errors at geometric edges do not grow with the filter on (the edge-stopping weights);
// - flicker, defined as the mean relative luminance change between consecutive frames after
//   re-projecting the previous frame with the G-buffer's motion vectors (nearest pixel,
//   second half of the sequence), is at least 5x lower with the denoiser than with the
//   raw frames (the target).
#include <cmath>

#include <gtest/gtest.h>

#include "core/builtin_scenes.h"
#include "core/error_metrics.h"
#include "gl/denoiser.h"
#include "hybrid/denoise_input.h"
#include "hybrid/hybrid_renderer.h"
#include "tests/gl/gl_test_util.h"
#include "tests/hybrid/reference_image.h"

namespace photovr {
namespace {

constexpr int kW = 48, kH = 54, kFrames = 32;

// The random sampler (Halton jitter, hashed path numbers), under which these bounds were
// set: the claims are about the denoiser's history, and the sampler moves the static
// error they are measured against. With Sobol the static error of this sequence falls
// 17 % (0.0116 -> 0.0097: stratified jitter) and the moving one is a property of the
// jitter sequence's last frames: over five 32-frame windows of each sequence it averaged
// 0.0231 (Halton) and 0.0238 (Sobol) while single windows ranged 0.015 .. 0.048, so the
// ratio of one window says nothing about Sobol. bench/bench_sampler.cpp measures the
// denoised error and flicker under both samplers.
constexpr SamplerKind kSampler = SamplerKind::Random;

// The camera drifts 2 mm and 0.05 degrees per frame (a slow head motion at 75 Hz: 15 cm/s).
EyeCamera cameraAt(const Scene& s, int frame, bool moving) {
  StereoRig rig;
  rig.head = poseOf(s.cameras.at(0));
  const float t = moving ? float(frame - (kFrames - 1)) : 0.0f;  // ends at the same pose
  rig.head.position.x += 0.002f * t;
  rig.head.orientation =
      glm::angleAxis(glm::radians(0.05f * t), glm::vec3(0, 1, 0)) * rig.head.orientation;
  return rig.eye(Eye::Left, kW, kH, samplePosition(kSampler, uint32_t(frame)));
}

// 512 spp at the sequence's final pose.
std::vector<glm::vec3> reference(const Scene& s) {
  return testing::referenceImage(s, cameraAt(s, kFrames - 1, false), 32, 16, 55);
}

struct Sequence {
  std::vector<glm::vec3> lastDenoised, lastRaw;
  gl::GBufferImage lastGBuffer;
  double flicker = 0.0;  // mean relative frame-to-frame change after re-projection
};

double luminance(const glm::vec3& c) {
  return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
}

// Mean |L_t(x) - L_{t-1}(x + motion)| / mean L over pixels whose history is on screen.
double reprojectedChange(const std::vector<glm::vec3>& now, const std::vector<glm::vec3>& before,
                         const gl::GBufferImage& g) {
  double diff = 0.0, sum = 0.0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const size_t i = g.index(x, y);
      if (g.visibility[i].x == kNoHitInstance) continue;
      const int px = int(std::lround(x + g.motion[i].x)), py = int(std::lround(y + g.motion[i].y));
      if (px < 0 || py < 0 || px >= kW || py >= kH) continue;
      diff += std::abs(luminance(now[i]) - luminance(before[g.index(px, py)]));
      sum += luminance(now[i]);
    }
  return sum > 0.0 ? diff / sum : 0.0;
}

Sequence run(const Scene& scene, bool moving, gl::DenoiseMode mode) {
  testing::osmesaContext();
  TraceSettings settings;
  settings.sampler = kSampler;
  HybridRenderer renderer(scene, kW, kH, settings);
  gl::Denoiser denoiser(kW, kH);
  Sequence s;
  std::vector<glm::vec3> previous;
  for (int f = 0; f < kFrames; ++f) {
    const EyeCamera cam = cameraAt(scene, f, moving);
    const EyeImage img = renderer.render({cam, cam}, 1, uint32_t(f), nullptr)[0];
    const DenoiseInput in = makeDenoiseInput(img);
    denoiser.run(renderer.gbuffer(), {in.eye, in.eye}, 1, mode, f == 0);
    std::vector<glm::vec3> out = denoiser.readLinear(0);
    const gl::GBufferImage g = renderer.gbuffer().read(0);
    if (f >= kFrames / 2) s.flicker += reprojectedChange(out, previous, g) / (kFrames / 2);
    previous = out;
    if (f == kFrames - 1) {
      s.lastDenoised = out;
      s.lastRaw = img.color;
      s.lastGBuffer = g;
    }
  }
  return s;
}

// Pixels whose 4-neighbourhood sees another instance or the background: geometric edges.
std::vector<bool> edgePixels(const gl::GBufferImage& g) {
  std::vector<bool> edge(size_t(kW) * kH, false);
  for (int y = 1; y + 1 < kH; ++y)
    for (int x = 1; x + 1 < kW; ++x) {
      const uint32_t id = g.visibility[g.index(x, y)].x;
      for (auto [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}})
        edge[g.index(x, y)] = edge[g.index(x, y)] || g.visibility[g.index(x + dx, y + dy)].x != id;
    }
  return edge;
}

double relMseWhere(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& ref,
                   const std::vector<bool>& mask, bool value) {
  double sum = 0.0;
  size_t n = 0;
  for (size_t i = 0; i < a.size(); ++i)
    if (mask[i] == value) sum += relMsePixel(a[i], ref[i]), ++n;
  return n ? sum / double(n) : 0.0;
}

TEST(DenoiseTemporal, MotionEdgesAndFlicker) {
  const Scene scene = makeBuiltinScene("cornell");
  const std::vector<glm::vec3> ref = reference(scene);
  const Sequence still = run(scene, false, gl::DenoiseMode::Full);
  const Sequence moving = run(scene, true, gl::DenoiseMode::Full);
  const Sequence raw = run(scene, true, gl::DenoiseMode::Off);
  const double eStill = relMse(still.lastDenoised, ref), eMoving = relMse(moving.lastDenoised, ref);
  RecordProperty("relmse_static_moving", std::to_string(eStill) + " " + std::to_string(eMoving));
  // The bound. Measured 0.0142 static, 0.0223 moving (1.6x): the resolve's
  // history is re-sampled every frame the camera moves and the light's outline bleeds a
  // little into the ceiling (bilinear re-sampling in linear HDR measured 3.8x).
  EXPECT_LT(eMoving, 2.0 * eStill) << "static " << eStill << ", moving " << eMoving;

  const std::vector<bool> edge = edgePixels(still.lastGBuffer);
  const double edgeOn = relMseWhere(still.lastDenoised, ref, edge, true);
  const double edgeOff = relMseWhere(still.lastRaw, ref, edge, true);
  const double restOn = relMseWhere(still.lastDenoised, ref, edge, false);
  const double restOff = relMseWhere(still.lastRaw, ref, edge, false);
  RecordProperty("edge_on_off_rest_on_off", std::to_string(edgeOn) + " " + std::to_string(edgeOff) +
                                                " " + std::to_string(restOn) + " " +
                                                std::to_string(restOff));
  // The filter must not blur edges into error: measured 2.95 -> 0.018 at edges, 2.23 ->
  // 0.013 elsewhere (before the resolve pass: 2.95 -> 1.02 and 2.23 -> 0.016). Edges
  // keep a little more of their error than flat areas (the weights stop the filter
  // there); the share may at most double: edge / rest with the filter 1.36, without 1.32.
  EXPECT_LT(edgeOn, edgeOff) << "the filter made edges worse";
  EXPECT_LT(restOn, restOff);
  EXPECT_LT(edgeOn / restOn, 2.0 * edgeOff / restOff) << "error moved to the edges";

  RecordProperty("flicker_full_off",
                 std::to_string(moving.flicker) + " " + std::to_string(raw.flicker));
  // The target is 5x. Measured 0.0111 vs 0.262 (24x); before the resolve pass
  // 0.119 (2.2x): the per-frame jitter moved edges, the light's outline and the metal
  // box's speckles, which SVGF's per-surface history does not average.
  EXPECT_LT(5.0 * moving.flicker, raw.flicker)
      << "full " << moving.flicker << ", off " << raw.flicker;
}

}  // namespace
}  // namespace photovr
