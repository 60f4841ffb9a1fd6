// The one-pass timewarp (gl/timewarp.h): its eye mode against the two-plane scene traced
// analytically (the same bounds as the grid re-projection's), the identity, and its panel
// mode against the reference chain it replaces (eye buffers -> Distorter -> PanelOutput).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "core/camera.h"
#include "core/error_metrics.h"
#include "gl/compositor.h"
#include "gl/eye_arrays.h"
#include "gl/panel_output.h"
#include "gl/timewarp.h"
#include "hmd/lens.h"
#include "shaders/compositor_shared.h"
#include "tests/gl/gl_test_util.h"
#include "tests/gl/two_plane_scene.h"

namespace photovr {
namespace {

using namespace photovr::testing;  // the two-plane scene

// Both eyes' colour and depth as the 2-layer arrays a rendered frame arrives in.
struct EyeArrays : gl::EyeArrays {
  EyeArrays(const std::array<EyeImage, 2>& eyes, int w, int h) : gl::EyeArrays(w, h) {
    for (int e = 0; e < 2; ++e) upload(e, eyes[e].color, eyes[e].depth);
  }
};

gl::LensParams smallPanel() {
  hmd::LensModel m;
  m.panel.hResolution = 192;  // a DK2 panel at 1/10 resolution, same optics
  m.panel.vResolution = 108;
  return hmd::flattenLens(m);
}

std::array<FovTangents, 2> dk2Fov() {
  return {FovTangents::dk2LeftEye(), FovTangents::dk2LeftEye().mirrored()};
}

std::array<ReprojectedEye, 2> runEyes(gl::Timewarp& t, const std::array<EyeImage, 2>& in,
                                      const std::array<EyeCamera, 2>& from,
                                      const std::array<EyeCamera, 2>& to) {
  const EyeArrays arrays(in, from[0].width, from[0].height);
  t.runEyes(arrays.color(), arrays.depth(), from, to);
  std::array<ReprojectedEye, 2> out;
  for (int e = 0; e < 2; ++e) out[e] = {t.readColor(e), t.readDepth(e)};
  return out;
}

TEST(Timewarp, TheSamePoseIsTheIdentity) {
  osmesaContext();
  gl::Timewarp t(smallPanel(), kW, kH, {kFov, kFov});
  Pose pose;
  pose.position = {0.1f, -0.05f, 0.2f};
  pose.orientation = glm::angleAxis(glm::radians(3.0f), glm::normalize(glm::vec3(0.3f, 1, 0.1f)));
  const std::array<EyeCamera, 2> cams = {camera(pose, {0.25f, -0.125f}), camera(pose)};
  const std::array<EyeImage, 2> eyes = {render(cams[0]), render(cams[1])};
  const auto out = runEyes(t, eyes, cams, cams);
  for (int e = 0; e < 2; ++e) {
    float maxErr = 0.0f, maxDepthErr = 0.0f;
    for (size_t i = 0; i < out[e].color.size(); ++i) {
      const glm::vec3 d = glm::abs(glm::vec3(out[e].color[i]) - glm::vec3(eyes[e].color[i]));
      maxErr = std::max(maxErr, std::max(d.x, std::max(d.y, d.z)));
      maxDepthErr =
          std::max(maxDepthErr, std::abs(out[e].depth[i] - eyes[e].depth[i]) / eyes[e].depth[i]);
      ASSERT_EQ(out[e].color[i].a, 1.0f) << "eye " << e << " pixel " << i;
    }
    std::printf("timewarp identity eye %d: max colour error %.2e, max relative depth error %.2e\n",
                e, maxErr, maxDepthErr);
    // Every B pixel lands on its own A texel centre, where the bilinear filter returns the
    // texel: only the half-float output rounds (values < 1: <= 2^-12).
    EXPECT_LT(maxErr, 1e-3f);
    EXPECT_LT(maxDepthErr, 1e-5f);  // float arithmetic on the same depth
    EXPECT_EQ(t.stats(e).reprojected, kW * kH);
  }
}

// The search against the analytic scene: the bounds the grid re-projection meets at grid
// step 1 (tests/gl/compositor_test.cpp), with the same 2-pixel silhouette margin.
TEST(Timewarp, ReprojectionToANearbyPoseMatchesTheAnalyticImage) {
  osmesaContext();
  gl::Timewarp t(smallPanel(), kW, kH, {kFov, kFov});
  checkNearbyPose("timewarp", 2, [&](const auto& in, const auto& from, const auto& to) {
    const auto out = runEyes(t, in, from, to);
    for (int e = 0; e < 2; ++e) {  // the counts are the outputs' origins (alpha)
      gl::ReprojectStats origins;
      for (const glm::vec4& c : out[e].color) {
        origins.reprojected += c.a == float(COMP_VALID);
        origins.filled += c.a == float(COMP_FILLED);
        origins.uncovered += c.a == 0.0f;
      }
      const gl::ReprojectStats s = t.stats(e);
      EXPECT_EQ(s.reprojected, origins.reprojected);
      EXPECT_EQ(s.filled, origins.filled);
      EXPECT_EQ(s.uncovered, origins.uncovered);
    }
    return out;
  });
}

// Eye buffers of the two-plane scene at the DK2's FOV.
std::array<EyeCamera, 2> dk2Eyes(const Pose& pose, int w, int h) {
  std::array<EyeCamera, 2> cams;
  for (int e = 0; e < 2; ++e) {
    cams[e] = camera(pose);
    cams[e].fov = dk2Fov()[e];
    cams[e].width = w, cams[e].height = h;
  }
  return cams;
}

// The reference chain: eye buffers through the Distorter's bilinear pass, then PanelOutput.
std::vector<glm::u8vec4> referencePanel(const gl::LensParams& lens, const EyeArrays& eyes, int w,
                                        int h, float exposure, int rotation) {
  gl::Distorter d(lens, w, h, dk2Fov());
  d.run(eyes.color());
  gl::PanelOutput out(lens.hResolution, lens.vResolution, rotation);
  out.run(d.panelTexture(), exposure);
  return out.read();
}

// At the rendered pose every panel pixel takes the distortion pass's tan-angles and taps.
// One depth everywhere: at a silhouette the timewarp drops the taps across it, which the
// distortion pass alone does not (the eye-mode tests cover silhouettes).
TEST(Timewarp, PanelAtTheRenderedPoseIsTheDistortionChain) {
  osmesaContext();
  const gl::LensParams lens = smallPanel();
  const int w = 48, h = 54;
  const auto cams = dk2Eyes(Pose{}, w, h);
  std::array<EyeImage, 2> flat = {render(cams[0]), render(cams[1])};
  for (auto& eye : flat) std::fill(eye.depth.begin(), eye.depth.end(), 0.05f);
  const EyeArrays eyes(flat, w, h);
  for (int rotation : {0, 90}) {
    gl::Timewarp t(lens, w, h, dk2Fov());
    gl::PanelOutput out(lens.hResolution, lens.vResolution, rotation);
    t.runPanel(eyes.color(), eyes.depth(), cams, cams, 1.5f, out);
    const PanelDifference d =
        panelDifference(out.read(), referencePanel(lens, eyes, w, h, 1.5f, rotation));
    std::printf(
        "timewarp panel vs distortion chain (rotation %d): %d visible pixels, mean %.3f, "
        "max %d levels\n",
        rotation, d.shown, d.meanLevels, d.maxLevels);
    EXPECT_GT(d.shown, lens.hResolution * lens.vResolution / 2);
    // The panel pass computes only the groups the lens shows and clears the rest: black
    // exactly where the chain is. Every lens-visible pixel is counted, as re-projected.
    EXPECT_EQ(d.blackInOne, 0);
    for (int e = 0; e < 2; ++e) EXPECT_EQ(t.stats(e).filled + t.stats(e).uncovered, 0);
    EXPECT_EQ(t.stats(0).reprojected + t.stats(1).reprojected, d.shown);
    // Same tan-angles, same bilinear taps: the chain only rounds its intermediate panel to
    // half float (2^-11 relative), which moves an 8-bit sRGB value by at most one level.
    EXPECT_LE(d.maxLevels, 1);
    EXPECT_LT(d.meanLevels, 0.1);
  }
}

// Without re-projection the panel is the distortion chain's, silhouettes included (both
// blend the taps across them), and the frame's depth is not needed.
TEST(Timewarp, PanelAsRenderedIsTheDistortionChain) {
  osmesaContext();
  const gl::LensParams lens = smallPanel();
  const int w = 48, h = 54;
  const auto cams = dk2Eyes(Pose{}, w, h);
  const EyeArrays eyes({render(cams[0]), render(cams[1])}, w, h);
  gl::Timewarp t(lens, w, h, dk2Fov());
  gl::PanelOutput out(lens.hResolution, lens.vResolution, 90);
  t.runPanelAsRendered(eyes.color(), cams, 1.5f, out);
  const PanelDifference d = panelDifference(out.read(), referencePanel(lens, eyes, w, h, 1.5f, 90));
  std::printf(
      "timewarp panel as rendered vs distortion chain: %d visible pixels, mean %.3f, max %d "
      "levels\n",
      d.shown, d.meanLevels, d.maxLevels);
  // As at the rendered pose above: the chain's half-float panel moves a value by <= 1 level.
  EXPECT_EQ(d.blackInOne, 0);
  EXPECT_GT(d.shown, lens.hResolution * lens.vResolution / 2);
  EXPECT_LE(d.maxLevels, 1);
  EXPECT_LT(d.meanLevels, 0.1);
  EXPECT_EQ(t.stats(0).reprojected + t.stats(1).reprojected, d.shown);
}

// The bench's floor pass (runPanelFloor) must do the work it stands for: on a frame of one
// colour, every output texel of the lens's groups shows that colour from the three taps
// (exact: the taps of a uniform image are the colour, stored as UNORM8 by rounding), and
// the rest of the panel stays black.
TEST(Timewarp, FloorPassTapsTheFrameOverTheLensGroups) {
  osmesaContext();
  const gl::LensParams lens = smallPanel();
  const int w = 48, h = 54;
  const auto cams = dk2Eyes(Pose{}, w, h);
  std::array<EyeImage, 2> flat = {render(cams[0]), render(cams[1])};
  for (auto& eye : flat) std::fill(eye.color.begin(), eye.color.end(), glm::vec4(0.2, 0.6, 1, 1));
  const EyeArrays eyes(flat, w, h);
  gl::Timewarp t(lens, w, h, dk2Fov());
  gl::PanelOutput out(lens.hResolution, lens.vResolution, 90);
  t.runPanelFloor(eyes.color(), eyes.depth(), cams, out);
  int coloured = 0, other = 0;
  for (const glm::u8vec4& p : out.read()) {
    if (p == glm::u8vec4(51, 153, 255, 255))
      ++coloured;
    else if (p != glm::u8vec4(0, 0, 0, 255))
      ++other;
  }
  EXPECT_EQ(other, 0);
  // The lens shows ~70 % of the panel; its 8x8 groups cover more.
  EXPECT_GT(coloured, lens.hResolution * lens.vResolution / 2);
}

// Moved head: the timewarp's panel of the frame rendered at A against the distortion chain
// on the frame traced at B. They differ where re-projection must guess (disocclusions,
// silhouettes), and by the resampling of two different pixel grids.
TEST(Timewarp, PanelAtANewPoseShowsTheSceneThere) {
  osmesaContext();
  const gl::LensParams lens = smallPanel();
  const int w = 48, h = 54;
  Pose b;
  b.position = {0.04f, 0.01f, -0.01f};
  b.orientation = glm::angleAxis(glm::radians(2.0f), glm::vec3(0, 1, 0));
  const auto from = dk2Eyes(Pose{}, w, h), to = dk2Eyes(b, w, h);
  const EyeArrays atA({render(from[0]), render(from[1])}, w, h);
  const EyeArrays atB({render(to[0]), render(to[1])}, w, h);
  gl::Timewarp t(lens, w, h, dk2Fov());
  gl::PanelOutput out(lens.hResolution, lens.vResolution, 90);
  t.runPanel(atA.color(), atA.depth(), from, to, 1.0f, out);
  const PanelDifference moved =
      panelDifference(out.read(), referencePanel(lens, atB, w, h, 1.0f, 90));
  // Without re-projection (A's frame shown as it was) for scale.
  t.runPanel(atA.color(), atA.depth(), from, from, 1.0f, out);
  const PanelDifference stale =
      panelDifference(out.read(), referencePanel(lens, atB, w, h, 1.0f, 90));
  int disoccluded = 0, visible = 0;
  for (int e = 0; e < 2; ++e) {
    const gl::ReprojectStats s = t.stats(e);
    visible += s.reprojected + s.filled + s.uncovered;
  }
  t.runPanel(atA.color(), atA.depth(), from, to, 1.0f, out);
  for (int e = 0; e < 2; ++e) disoccluded += t.stats(e).filled + t.stats(e).uncovered;
  std::printf(
      "timewarp panel at a moved pose vs the scene traced there: mean %.3f levels "
      "(stale frame %.3f); disoccluded %d of %d lens-visible pixels\n",
      moved.meanLevels, stale.meanLevels, disoccluded, visible);
  // Measured: 0.88 levels against 2.86 for the stale frame. What remains is the resampling
  // of two pixel grids (each panel pixel interpolates A's texels, the reference B's) and
  // the disocclusions, filled from the background side instead of with what B sees.
  EXPECT_LT(moved.meanLevels, stale.meanLevels / 2.5);
  EXPECT_LT(moved.meanLevels, 1.5);
  EXPECT_GT(disoccluded, 0);
}

std::array<EyeCamera, 2> layoutEyes(const Pose& pose, const StereoLayout& l) {
  std::array<EyeCamera, 2> cams;
  for (int e = 0; e < 2; ++e) {
    cams[e] = camera(pose);
    cams[e].fov = l.fov(Eye(e));
    cams[e].width = l.width, cams[e].height = l.height;
  }
  return cams;
}

// What the panel at a turned head shows from a frame rendered in 'l' before the turn.
struct TurnedPanel {
  std::vector<glm::u8vec4> panel;
  int uncovered = 0, filled = 0;
};

TurnedPanel panelAfterTurn(const gl::LensParams& lens, const StereoLayout& l, const Pose& b) {
  const auto from = layoutEyes(Pose{}, l), to = layoutEyes(b, l);
  const EyeArrays atA({render(from[0]), render(from[1])}, l.width, l.height);
  gl::Timewarp t(lens, l.width, l.height, {l.fov(Eye::Left), l.fov(Eye::Right)});
  t.setShownField({l.field(Eye::Left), l.field(Eye::Right)});
  gl::PanelOutput out(lens.hResolution, lens.vResolution, 90);
  t.runPanel(atA.color(), atA.depth(), from, to, 1.0f, out);
  TurnedPanel r{out.read()};
  for (int e = 0; e < 2; ++e) r.uncovered += t.stats(e).uncovered, r.filled += t.stats(e).filled;
  return r;
}

TEST(Timewarp, OverscanLeavesNothingUncoveredForATurnWithinIt) {
  osmesaContext();
  const gl::LensParams lens = smallPanel();
  const int w = 48, h = 54;
  Pose b;  // 2.5 deg about a diagonal axis: the corners' case (core/camera.h widened)
  b.orientation = glm::angleAxis(glm::radians(2.5f), glm::normalize(glm::vec3(1, 1, 0)));
  const StereoLayout plain = StereoLayout::dk2(w, h);
  const StereoLayout over = StereoLayout::dk2(w, h, glm::radians(3.0f));
  const TurnedPanel without = panelAfterTurn(lens, plain, b);
  const TurnedPanel with = panelAfterTurn(lens, over, b);
  // The truth: the plain layout rendered at B (the panel shows the field whatever the margin).
  const auto atBCams = dk2Eyes(b, w, h);
  const EyeArrays atB({render(atBCams[0]), render(atBCams[1])}, w, h);
  const auto truth = referencePanel(lens, atB, w, h, 1.0f, 90);
  const PanelDifference dWithout = panelDifference(without.panel, truth);
  const PanelDifference dWith = panelDifference(with.panel, truth);
  std::printf(
      "2.5 deg turn: uncovered %d without overscan, %d with 3 deg; black in one %d / %d; "
      "mean %.3f / %.3f levels\n",
      without.uncovered, with.uncovered, dWithout.blackInOne, dWith.blackInOne, dWithout.meanLevels,
      dWith.meanLevels);
  EXPECT_GT(without.uncovered, 0);  // the strip the turn brings in
  EXPECT_GT(dWithout.blackInOne, 0);
  // A pure rotation disoccludes nothing; within the margin every direction is rendered.
  EXPECT_EQ(with.uncovered, 0);
  EXPECT_EQ(with.filled, 0);
  EXPECT_EQ(dWith.blackInOne, 0);
  // Where both show the scene, overscan resamples as finely as the plain layout (the same
  // pixels per tan-angle): the bound of PanelAtANewPoseShowsTheSceneThere.
  EXPECT_LT(dWith.meanLevels, 1.5);
}

}  // namespace
}  // namespace photovr
