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

namespace photovr {
namespace {

constexpr int kW = 64, kH = 48;
const FovTangents kFov{0.55f, 0.5f, 0.45f, 0.4f};

// Scene: a background plane z = -3 (blue-ish, smooth pattern) and a foreground square
// z = -1.5, |x|, |y| <= 0.3 (red-ish). Smooth patterns keep the resampling error small.
glm::vec3 background(glm::vec3 p) {
  return {0.2f + 0.1f * std::sin(2.0f * p.x), 0.4f + 0.2f * std::sin(1.7f * p.y + 0.3f),
          0.8f + 0.15f * std::cos(1.3f * p.x + 1.1f * p.y)};
}
glm::vec3 foreground(glm::vec3 p) {
  return {0.85f + 0.1f * std::sin(6.0f * p.x), 0.3f + 0.2f * std::cos(5.0f * p.y), 0.1f};
}

struct Hit {
  glm::vec3 color;
  float distance;  // view distance (along the camera's -Z)
  bool front;
};

// Ray through window coordinates (px, py) of a camera, intersected with the scene.
Hit trace(const EyeCamera& cam, float px, float py) {
  const glm::vec3 eyeDir(-cam.fov.left + px * (cam.fov.left + cam.fov.right) / cam.width,
                         -cam.fov.down + py * (cam.fov.up + cam.fov.down) / cam.height, -1.0f);
  const glm::vec3 d = glm::mat3_cast(cam.pose.orientation) * eyeDir;
  const glm::vec3 o = cam.pose.position;
  const float tf = (-1.5f - o.z) / d.z;
  const glm::vec3 pf = o + tf * d;
  if (tf > 0.0f && std::abs(pf.x) <= 0.3f && std::abs(pf.y) <= 0.3f)
    return {foreground(pf), tf, true};
  const float tb = (-3.0f - o.z) / d.z;
  return {background(o + tb * d), tb, false};
}

struct EyeImage {
  std::vector<glm::vec4> color;
  std::vector<float> depth;
  std::vector<uint8_t> front;
};

EyeImage render(const EyeCamera& cam) {
  EyeImage img;
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      const Hit h = trace(cam, x + 0.5f + cam.jitter.x, y + 0.5f + cam.jitter.y);
      img.color.emplace_back(h.color, 1.0f);
      img.depth.push_back(cam.depthAt(h.distance));
      img.front.push_back(h.front);
    }
  return img;
}

EyeCamera camera(const Pose& pose, glm::vec2 jitter = glm::vec2(0.0f)) {
  EyeCamera c;
  c.pose = pose;
  c.fov = kFov;
  c.width = kW;
  c.height = kH;
  c.jitter = jitter;
  return c;
}

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

// Re-projects the two-plane scene with one grid vertex every 'step' pixels and compares
// with the scene rendered at pose B.
void checkNearbyPose(int step) {
  testing::osmesaContext();
  gl::ReprojectParams params;
  params.gridStep = step;
  gl::Reprojector r(kW, kH, params);
  Pose a;
  Pose b;
  b.position = {0.1f, 0.03f, -0.02f};  // 2 px of parallax between the planes
  b.orientation = glm::angleAxis(glm::radians(2.5f), glm::vec3(0, 1, 0)) *
                  glm::angleAxis(glm::radians(-1.0f), glm::vec3(1, 0, 0));
  const std::array<EyeCamera, 2> from = {camera(a, {0.2f, 0.3f}), camera(a)};
  const std::array<EyeCamera, 2> to = {camera(b, {-0.1f, 0.2f}), camera(b)};
  for (int e = 0; e < 2; ++e) {
    const EyeImage in = render(from[e]);
    r.upload(e, in.color.data(), in.depth.data());
  }
  r.run(from, to);
  for (int e = 0; e < 2; ++e) {
    const EyeImage truth = render(to[e]);
    const auto out = r.readColor(e);
    const auto depth = r.readDepth(e);
    double errValid = 0.0, depthErr = 0.0, errInterior = 0.0, maxInterior = 0.0;
    int nInterior = 0;
    int valid = 0, filled = 0, uncovered = 0, filledBackground = 0;
    // Expected disocclusion: B pixels showing background that A does not see (hidden by
    // the square, or outside A's frustum).
    int expected = 0;
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        const size_t i = size_t(y) * kW + x;
        const glm::vec4 o = out[i];
        if (o.a > 0.75f) {
          ++valid;
          const glm::vec3 d = glm::abs(glm::vec3(o) - glm::vec3(truth.color[i]));
          errValid += (d.x + d.y + d.z) / 3.0;
          // Interior: the truth's neighbourhood of radius 1 + step shows one surface (away
          // from the square's silhouette, where any pixel-sampled edge is off by up to a
          // pixel, and a grid cell across the edge reaches 'step' pixels further).
          const int m = 1 + step;
          bool interior = x >= m && y >= m && x + m < kW && y + m < kH;
          for (int dy = -m; dy <= m && interior; ++dy)
            for (int dx = -m; dx <= m; ++dx)
              interior = interior && truth.front[i + dy * kW + dx] == truth.front[i];
          if (interior) {
            ++nInterior;
            errInterior += (d.x + d.y + d.z) / 3.0;
            maxInterior = std::max(maxInterior, double(std::max(d.x, std::max(d.y, d.z))));
            depthErr += std::abs(depth[i] - truth.depth[i]) / truth.depth[i];
          }
        } else if (o.a > 0.25f) {
          ++filled;
          filledBackground += o.b > o.r;  // background is blue-ish, the square red-ish
        } else {
          ++uncovered;
        }
        // Where is B's hit as seen from A?
        const EyeCamera& cb = to[e];
        const glm::vec3 eyeDir(
            -cb.fov.left + (x + 0.5f + cb.jitter.x) * (cb.fov.left + cb.fov.right) / kW,
            -cb.fov.down + (y + 0.5f + cb.jitter.y) * (cb.fov.up + cb.fov.down) / kH, -1.0f);
        const glm::vec3 world = cb.pose.position + glm::mat3_cast(cb.pose.orientation) * eyeDir *
                                                       (cb.znear / truth.depth[i]);
        const glm::vec4 inA = from[e].view() * glm::vec4(world, 1.0f);
        const float tx = inA.x / -inA.z, ty = inA.y / -inA.z;
        const float ax = (tx + kFov.left) * kW / (kFov.left + kFov.right) - from[e].jitter.x;
        const float ay = (ty + kFov.down) * kH / (kFov.up + kFov.down) - from[e].jitter.y;
        if (ax < 0 || ay < 0 || ax > kW || ay > kH) {
          ++expected;
        } else if (!truth.front[i]) {
          const Hit h = trace(from[e], ax, ay);
          expected += h.front;
        }
      }
    const int n = kW * kH;
    const double meanErr = errValid / std::max(valid, 1);
    const double measured = double(filled + uncovered) / n;
    std::printf(
        "reprojection (grid step %d) eye %d: mean abs colour error %.2e over %d re-projected "
        "pixels; interior "
        "(%d px) mean %.2e, max %.2e, mean relative depth error %.2e; disoccluded %.4f (filled %d, "
        "uncovered %d; %d filled from the background), analytic %.4f\n",
        step, e, meanErr, valid, nInterior, errInterior / nInterior, maxInterior,
        depthErr / nInterior, measured, filled, uncovered, filledBackground, double(expected) / n);
    EXPECT_LT(meanErr, 0.03);
    EXPECT_LT(errInterior / nInterior, 1e-3);
    EXPECT_LT(maxInterior, 5e-3);
    EXPECT_LT(depthErr / nInterior, 1e-4);
    EXPECT_GT(filled, 0);
    EXPECT_GE(filledBackground, filled * 9 / 10);
    EXPECT_NEAR(measured, double(expected) / n, 0.3 * double(expected) / n + 8.0 / n);
  }
}

TEST(Compositor, ReprojectionToANearbyPoseMatchesTheAnalyticImage) {
  checkNearbyPose(1);
}

// A coarser grid is still exact on the planes (a homography interpolated perspective-
// correctly); only the cells across the square's edge differ, within the same bounds.
TEST(Compositor, CoarseGridReprojectionMatchesTheAnalyticImage) {
  checkNearbyPose(2);
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
  gl::Distorter d(gl::lensParamsOf(m), ew, eh, fov);
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
