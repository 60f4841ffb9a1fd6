// The headset compositor's passes against analytic images and the CPU lens model:
// re-projection to the same pose is the identity; re-projection of a synthetic two-plane
// scene to a nearby pose matches that scene rendered analytically there (disocclusions
// filled from the background); the distortion pass samples the tan-angles of
// hmd::screenToTan and reads exactly the eye-buffer texels hmd's hidden-area mask keeps.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "core/camera.h"
#include "gl/compositor.h"
#include "hmd/lens.h"
#include "hmd/lens_maps.h"
#include "tests/gl/gl_test_util.h"
#include "tests/gl/two_plane_scene.h"

namespace photovr {
namespace {

using namespace photovr::testing;  // the two-plane scene

TEST(Compositor, ReprojectionToTheSamePoseIsTheIdentity) {
  testing::osmesaContext();
  gl::Reprojector r(kW, kH);
  Pose pose;
  pose.position = {0.1f, -0.05f, 0.2f};
  pose.orientation = glm::angleAxis(glm::radians(3.0f), glm::normalize(glm::vec3(0.3f, 1, 0.1f)));
  const std::array<EyeCamera, 2> cams = {camera(pose, {0.25f, -0.125f}), camera(pose)};
  const EyeImage eyes[2] = {render(cams[0]), render(cams[1])};
  for (int e = 0; e < 2; ++e) r.upload(e, eyes[e].color.data(), eyes[e].depth.data());
  r.run(cams, cams);
  for (int e = 0; e < 2; ++e) {
    const auto out = r.readColor(e);
    const auto depth = r.readDepth(e);
    float maxErr = 0.0f, maxDepthErr = 0.0f;
    for (size_t i = 0; i < out.size(); ++i) {
      const glm::vec3 d = glm::abs(glm::vec3(out[i]) - glm::vec3(eyes[e].color[i]));
      maxErr = std::max(maxErr, std::max(d.x, std::max(d.y, d.z)));
      maxDepthErr = std::max(maxDepthErr, std::abs(depth[i] - eyes[e].depth[i]) / eyes[e].depth[i]);
      ASSERT_EQ(out[i].a, 1.0f) << "eye " << e << " pixel " << i;
    }
    std::printf("identity eye %d: max colour error %.2e, max relative depth error %.2e\n", e,
                maxErr, maxDepthErr);
    EXPECT_LT(maxErr, 1e-3f);  // half-float output: values < 1 round to <= 2^-12
    EXPECT_LT(maxDepthErr, 1e-5f);
    EXPECT_EQ(r.stats(e).disoccludedFraction(), 0.0);
  }
}

// The grid re-projection with one vertex every 'step' pixels.
void checkGridAtNearbyPose(int step) {
  osmesaContext();
  gl::ReprojectParams params;
  params.gridStep = step;
  gl::Reprojector r(kW, kH, params);
  char label[32];
  std::snprintf(label, sizeof label, "grid step %d", step);
  checkNearbyPose(label, 1 + step, [&](const auto& in, const auto& from, const auto& to) {
    for (int e = 0; e < 2; ++e) r.upload(e, in[e].color.data(), in[e].depth.data());
    r.run(from, to);
    std::array<ReprojectedEye, 2> out;
    for (int e = 0; e < 2; ++e) out[e] = {r.readColor(e), r.readDepth(e)};
    return out;
  });
}

TEST(Compositor, ReprojectionToANearbyPoseMatchesTheAnalyticImage) {
  checkGridAtNearbyPose(1);
}

// A coarser grid is still exact on the planes (a homography interpolated perspective-
// correctly); only the cells across the square's edge differ, within the same bounds.
TEST(Compositor, CoarseGridReprojectionMatchesTheAnalyticImage) {
  checkGridAtNearbyPose(2);
}

TEST(Compositor, DistortionSamplesTheLensModelAndItsVisibleArea) {
  testing::osmesaContext();
  hmd::LensModel m;
  m.panel.hResolution = 192;  // a DK2 panel at 1/10 resolution, same optics
  m.panel.vResolution = 108;
  const int ew = 48, eh = 54;  // eye buffer: half the display's pixel count per axis
  const std::array<FovTangents, 2> fov = {FovTangents::dk2LeftEye(),
                                          FovTangents::dk2LeftEye().mirrored()};
  // Eye buffer contents: any smooth image; routed through an identity re-projection so the
  // compositor's own chain feeds the distortion pass.
  gl::Reprojector r(ew, eh);
  std::array<EyeCamera, 2> cams;
  std::vector<glm::vec4> color[2];
  for (int e = 0; e < 2; ++e) {
    cams[e].fov = fov[e];
    cams[e].width = ew;
    cams[e].height = eh;
    std::vector<float> depth(size_t(ew) * eh, 0.05f);
    for (int y = 0; y < eh; ++y)
      for (int x = 0; x < ew; ++x)
        color[e].emplace_back(0.5f + 0.4f * std::sin(0.3f * x + e),
                              0.5f + 0.4f * std::cos(0.2f * y), float(x + y) / (ew + eh), 1.0f);
    r.upload(e, color[e].data(), depth.data());
  }
  r.run(cams, cams);
  gl::Distorter d(hmd::flattenLens(m), ew, eh, fov);
  for (int e = 0; e < 2; ++e) {
    const glm::vec2 c = d.lensCentre(e);
    const glm::dvec2 ref = hmd::lensCentre(m.panel, Eye(e));
    EXPECT_NEAR(c.x, ref.x, 1e-6);
    EXPECT_NEAR(c.y, ref.y, 1e-6);
  }
  d.run(r.colorTexture(), 2, true);
  const auto samples = d.readSamples();
  const auto panel = d.readPanel();
  const int pw = m.panel.hResolution, ph = m.panel.vResolution, dw = pw / 2;
  const hmd::Channel channels[3] = {hmd::Channel::Red, hmd::Channel::Green, hmd::Channel::Blue};
  for (int e = 0; e < 2; ++e) {
    const auto eyeColor = r.readColor(e);
    double maxTanErr = 0.0, maxColorErr = 0.0;
    int seen = 0, seesMismatch = 0, notBlack = 0;
    for (int py = 0; py < ph; ++py)
      for (int px = 0; px < dw; ++px) {
        const size_t i = size_t(py) * pw + e * dw + px;
        const glm::dvec2 screen((px + 0.5) * 2.0 / dw - 1.0, (py + 0.5) * 2.0 / ph - 1.0);
        const bool sees = hmd::lensSees(m, Eye(e), screen);
        seesMismatch += sees != samples[i].sees;
        for (int ch = 0; ch < 3; ++ch) {
          const glm::dvec2 t = hmd::screenToTan(m, Eye(e), screen, channels[ch]);
          maxTanErr = std::max(maxTanErr, glm::length(t - glm::dvec2(samples[i].tan[ch])));
          if (!sees) continue;
          // CPU bilinear sample of the (half-float) eye buffer at that tan-angle.
          const glm::dvec2 p = hmd::tanToEyeBuffer(fov[e], ew, eh, t) - 0.5;
          const int x0 = int(std::floor(p.x)), y0 = int(std::floor(p.y));
          const double fx = p.x - x0, fy = p.y - y0;
          auto at = [&](int x, int y) {
            x = std::clamp(x, 0, ew - 1), y = std::clamp(y, 0, eh - 1);
            return double(eyeColor[size_t(y) * ew + x][ch]);
          };
          const double v = (1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x0 + 1, y0)) +
                           fy * ((1 - fx) * at(x0, y0 + 1) + fx * at(x0 + 1, y0 + 1));
          maxColorErr = std::max(maxColorErr, std::abs(v - panel[i][ch]));
        }
        seen += sees;
        if (!sees) notBlack += panel[i].r != 0.0f || panel[i].g != 0.0f || panel[i].b != 0.0f;
      }
    // Footprint against the CPU masks.
    const hmd::EyeBufferSpec spec{Eye(e), fov[e], ew, eh};
    const auto read = d.readFootprint(e);
    const auto hidden1 = hmd::hiddenAreaMask(m, spec, 1);
    const auto hidden0 = hmd::hiddenAreaMask(m, spec, 0);
    const auto reference = hmd::distortionFootprint(m, spec);
    int readHidden = 0, unreadVisible = 0, vsReference = 0, hiddenCount = 0;
    for (size_t i = 0; i < read.size(); ++i) {
      readHidden += read[i] && hidden1[i];
      unreadVisible += !read[i] && !hidden0[i];
      vsReference += read[i] != reference[i];
      hiddenCount += hidden1[i];
    }
    std::printf(
        "distortion eye %d: max tan error %.2e, max colour error %.2e, %d of %d display pixels "
        "seen (%d lensSees mismatches, %d unseen not black); footprint: %d read texels hidden "
        "(mask hides %d), %d visible texels unread, %d differ from hmd::distortionFootprint\n",
        e, maxTanErr, maxColorErr, seen, dw * ph, seesMismatch, notBlack, readHidden, hiddenCount,
        unreadVisible, vsReference);
    EXPECT_LT(maxTanErr, 1e-4);
    EXPECT_LT(maxColorErr, 2e-3);
    EXPECT_EQ(seesMismatch, 0);
    EXPECT_EQ(notBlack, 0);
    EXPECT_GT(hiddenCount, 0);
    EXPECT_EQ(readHidden, 0);
    EXPECT_EQ(unreadVisible, 0);
    EXPECT_LE(vsReference, 2);  // float vs double at a tap boundary
  }
  // The display run (no footprint) samples through the texture unit's bilinear filter
  // instead of four explicit taps; the panel must be the debug run's.
  d.run(r.colorTexture(), 2, false);
  const auto fast = d.readPanel();
  double maxFastErr = 0.0;
  for (size_t i = 0; i < fast.size(); ++i)
    for (int ch = 0; ch < 3; ++ch)
      maxFastErr = std::max(maxFastErr, double(std::abs(fast[i][ch] - panel[i][ch])));
  std::printf("distortion through the bilinear sampler: max difference %.2e\n", maxFastErr);
  // llvmpipe quantises filter weights to 8 bits: up to 1/256 of the largest difference
  // between neighbouring texels (~0.05 in this image), plus the half-float panel's rounding.
  EXPECT_LT(maxFastErr, 2e-3);
}

}  // namespace
}  // namespace photovr
