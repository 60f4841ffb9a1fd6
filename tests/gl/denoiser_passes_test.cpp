// Each SVGF pass on a tiny two-layer image against the CPU version of its math
// (tests/gl/denoiser_test_util.h): reprojection with disocclusion rejection, moments and
// variance, a-trous iterations, compositing and tone mapping.
#include <cstdint>
#include <string>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/tonemap.h"
#include "gl/denoiser.h"
#include "tests/gl/denoiser_test_util.h"
#include "tests/gl/gl_test_util.h"

namespace photovr {
namespace {

using testing::cpuTemporal;
using testing::kBackground;
using testing::PreviousFrame;
using testing::SyntheticFrame;
using testing::SyntheticGBuffer;
using testing::toHalf;

constexpr int kW = 8, kH = 6;
// Outputs are stored as half floats: 11 significant bits, relative rounding <= 2^-11;
// inputs that came from half-float history add another rounding. 2e-3 covers both with
// margin; the absolute term covers values near zero.
constexpr float kHalfTol = 2e-3f;

float hash01(uint32_t v) {
  v ^= v >> 16;
  v *= 0x7feb352dU;
  v ^= v >> 15;
  v *= 0x846ca68bU;
  v ^= v >> 16;
  return float(v & 0xFFFFFF) / float(0x1000000);
}
glm::vec3 noise(int x, int y, int e, int t, int channel, float scale) {
  const uint32_t s = uint32_t(((t * 2 + e) * 64 + y) * 64 + x) * 8 + uint32_t(channel) * 3;
  return scale * glm::vec3(hash01(s), hash01(s + 1), hash01(s + 2));
}

// Frame t. Layer 0 scrolls left by one pixel per frame (motion +1, 0): a tilted plane
// (instance 0, triangles in 3-pixel blocks) and a box (instance 1) ride along; pixel (3, 0)
// is background. At t = 1 a 3x3 block jumps 2x in depth on the same instance and
// another instance appears in the lower right. Layer 1 is static with motion (0.5, 0.25):
// bilinear taps straddle the box, the image border and a curved surface.
SyntheticFrame tinyFrame(int t) {
  SyntheticFrame f(kW, kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const int sx = x + t;
      const size_t i = f.index(x, y);
      if (!(x == 3 && y == 0)) {
        const bool box = sx >= 5 && sx <= 6 && y >= 2 && y <= 3;
        float depth = box ? 0.3f : 0.1f + 0.004f * float(sx) + 0.002f * float(y);
        const bool jump = t == 1 && x >= 1 && x <= 3 && y >= 3;
        const bool newcomer = t == 1 && x >= 5 && y >= 4;
        if (jump) depth *= 2.0f;
        f.setSurface(0, x, y, box ? 1 : (newcomer ? 2 : 0), box ? 7 : unsigned(sx / 3), depth,
                     box ? glm::vec3(0.6f, 0.0f, 0.8f) : glm::vec3(0, 0, 1));
        f.layer[0].roughness[i] = box ? 0.2f : 1.0f;
      }
      f.layer[0].motion[i] = glm::vec2(1.0f, 0.0f);
      const bool box1 = x >= 2 && x <= 3 && y >= 1 && y <= 3;
      // The plane's normal turns ~0.3 per pixel: its bilinear taps pass the normal test
      // only through its slope term (Falcor's fwidth).
      f.setSurface(
          1, x, y, box1 ? 1 : 0, 0, box1 ? 0.25f : 0.2f - 0.01f * float(x),
          box1 ? glm::vec3(0, 0.6f, 0.8f) : glm::normalize(glm::vec3(0.3f * float(x - 4), 0, 1)));
      f.layer[1].roughness[i] = box1 ? 0.5f : 0.8f;
      f.layer[1].motion[i] = glm::vec2(0.5f, 0.25f);
      for (int e = 0; e < 2; ++e) {
        const bool bg = f.layer[e].visibility[i].x == kBackground;
        f.layer[e].diffuse[i] = bg ? glm::vec3(0) : noise(x + t, y, e, t, 0, 2.0f);
        f.layer[e].specular[i] = bg ? glm::vec3(0) : noise(x + t, y, e, t, 1, 1.0f);
      }
    }
  return f;
}

void expectNear4(const glm::vec4& gpu, const glm::vec4& cpu, const std::string& what) {
  for (int k = 0; k < 4; ++k)
    EXPECT_NEAR(gpu[k], cpu[k], kHalfTol * std::abs(cpu[k]) + 1e-4f) << what << " [" << k << "]";
}

std::string at(int e, int x, int y) {
  return "eye " + std::to_string(e) + " (" + std::to_string(x) + ", " + std::to_string(y) + ")";
}

PreviousFrame readBack(const gl::Denoiser& dn, const SyntheticFrame& f) {
  PreviousFrame p{&f, {}, {}, {}, {}};
  for (int e = 0; e < 2; ++e) {
    p.diffuse[e] = dn.readStage(0, false, e);
    p.specular[e] = dn.readStage(0, true, e);
    p.moments[e] = dn.readMoments(e);
    p.aux[e] = dn.readAux(e);
  }
  return p;
}

// Compares the temporal pass's outputs of the last run with the CPU version.
void expectTemporalMatches(const gl::DenoiseParams& params, const PreviousFrame& got,
                           const SyntheticFrame& f, const PreviousFrame* prev) {
  for (int e = 0; e < 2; ++e)
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        const size_t i = f.index(x, y);
        if (f.layer[e].visibility[i].x == kBackground) {
          EXPECT_EQ(got.aux[e][i].x, 0.0f) << at(e, x, y);
          continue;
        }
        const testing::CpuTemporal c = cpuTemporal(params, f, prev, e, x, y);
        expectNear4(got.diffuse[e][i], c.diffuse, "diffuse " + at(e, x, y));
        expectNear4(got.specular[e][i], c.specular, "specular " + at(e, x, y));
        expectNear4(got.moments[e][i], c.moments, "moments " + at(e, x, y));
        EXPECT_EQ(got.aux[e][i].x, c.length) << "history length " + at(e, x, y);
        const glm::vec2 g = testing::cpuRelativeGradient(f, e, x, y);
        EXPECT_NEAR(got.aux[e][i].y, g.x, kHalfTol * std::abs(g.x) + 1e-6f) << at(e, x, y);
        EXPECT_NEAR(got.aux[e][i].z, g.y, kHalfTol * std::abs(g.y) + 1e-6f) << at(e, x, y);
        EXPECT_EQ(got.aux[e][i].w, toHalf(f.layer[e].roughness[i])) << at(e, x, y);
      }
}

TEST(DenoiserPasses, TemporalReprojectionAndRejectionMatchCpu) {
  testing::osmesaContext();
  gl::DenoiseParams params;
  params.temporalVarianceFrames = 2;  // frame 2: temporal variance where history holds
  gl::Denoiser dn(kW, kH, params);
  SyntheticGBuffer gbuffer(kW, kH);
  const SyntheticFrame f0 = tinyFrame(0), f1 = tinyFrame(1);

  gbuffer.upload(f0);
  dn.run(gbuffer.geometry(), f0.eyes(), 2, gl::DenoiseMode::Temporal, true);
  const PreviousFrame first = readBack(dn, f0);
  expectTemporalMatches(params, first, f0, nullptr);  // all spatial variance (§4.2)

  gbuffer.upload(f1);
  dn.run(gbuffer.geometry(), f1.eyes(), 2, gl::DenoiseMode::Temporal, false);
  const PreviousFrame second = readBack(dn, f1);
  expectTemporalMatches(params, second, f1, &first);

  // The rejections the scene was built for, independent of the CPU version.
  auto length = [&](int e, int x, int y) { return second.aux[e][f1.index(x, y)].x; };
  // (Pixels whose bilinear taps fail but which have a consistent pixel in the 3x3 around
  // the back-projected position keep their history: Falcor's fallback, checked above.)
  EXPECT_EQ(length(0, 2, 4), 1.0f) << "depth jump on the same instance";
  EXPECT_EQ(length(0, 6, 5), 1.0f) << "another instance";
  EXPECT_EQ(length(0, 3, 0), 0.0f) << "background keeps no history";
  EXPECT_EQ(length(0, 4, 2), 2.0f) << "box interior follows the motion";
  EXPECT_EQ(length(0, 1, 1), 2.0f) << "plane interior follows the motion";
}

TEST(DenoiserPasses, TriangleTestCanBeSwitchedOff) {
  testing::osmesaContext();
  gl::DenoiseParams params;
  gl::Denoiser dn(kW, kH, params);
  SyntheticGBuffer gbuffer(kW, kH);
  SyntheticFrame a = tinyFrame(0);
  for (auto& m : a.layer[0].motion) m = glm::vec2(0);
  SyntheticFrame b = a;
  for (auto& v : b.layer[0].visibility)
    if (v.x != kBackground) v.y += 1;  // the same surfaces, named as other triangles
  for (bool require : {true, false}) {
    params.requireSameTriangle = require;
    dn.setParams(params);
    gbuffer.upload(a);
    dn.run(gbuffer.geometry(), a.eyes(), 1, gl::DenoiseMode::Temporal, true);
    gbuffer.upload(b);
    dn.run(gbuffer.geometry(), b.eyes(), 1, gl::DenoiseMode::Temporal, false);
    EXPECT_EQ(dn.readAux(0)[a.index(4, 4)].x, require ? 1.0f : 2.0f) << require;
  }
}

// The firefly clamp and two a-trous iterations. With a clamp factor of 1 (plain
// rank-conditioned rank selection) tinyFrame's uniform noise leaves about one pixel in
// nine brighter than all its neighbours: the clamp acts.
TEST(DenoiserPasses, AtrousIterationsMatchCpu) {
  testing::osmesaContext();
  gl::DenoiseParams params;
  params.iterations = 2;  // stages 0 (temporal), 1 (step 1) and 2 (step 2) all stay intact
  params.fireflyFactor = 1.0f;
  gl::Denoiser dn(kW, kH, params);
  SyntheticGBuffer gbuffer(kW, kH);
  const SyntheticFrame f = tinyFrame(0);
  gbuffer.upload(f);
  dn.run(gbuffer.geometry(), f.eyes(), 2, gl::DenoiseMode::Full, true);
  for (int e = 0; e < 2; ++e) {
    const auto aux = dn.readAux(e);
    // Iteration 0 filters the temporal output after the firefly clamp.
    auto in = testing::CpuAtrousOut{testing::cpuFirefly(params, f, e, dn.readStage(0, false, e)),
                                    testing::cpuFirefly(params, f, e, dn.readStage(0, true, e))};
    for (int stage = 1; stage <= 2; ++stage) {
      const int step = 1 << (stage - 1);
      const auto cpu = testing::cpuAtrous(params, f, e, in.diffuse, in.specular, aux, step);
      const auto gd = dn.readStage(stage, false, e), gs = dn.readStage(stage, true, e);
      for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
          const size_t i = f.index(x, y);
          const std::string where = "step " + std::to_string(step) + " " + at(e, x, y);
          expectNear4(gd[i], cpu.diffuse[i], "diffuse " + where);
          expectNear4(gs[i], cpu.specular[i], "specular " + where);
        }
      in = {gd, gs};  // the next iteration starts from the GPU's (half-float) output
    }
  }
}

TEST(DenoiserPasses, CompositeMatchesCpuToneMap) {
  testing::osmesaContext();
  gl::DenoiseParams params;
  params.exposure = 1.7f;
  gl::Denoiser dn(kW, kH, params);
  SyntheticGBuffer gbuffer(kW, kH);
  SyntheticFrame f = tinyFrame(0);
  for (int e = 0; e < 2; ++e)
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        const size_t i = f.index(x, y);
        f.layer[e].diffuse[i] = noise(x, y, e, 5, 2, 3.0f);  // up to 3: the shoulder too
        f.layer[e].specular[i] = noise(x, y, e, 5, 3, 1.0f);
        f.layer[e].diffuseAlbedo[i] = noise(x, y, e, 5, 4, 1.0f);
        f.layer[e].specularAlbedo[i] = noise(x, y, e, 5, 5, 0.5f);
        f.layer[e].unfiltered[i] = noise(x, y, e, 5, 6, 0.5f);
      }
  gbuffer.upload(f);
  dn.run(gbuffer.geometry(), f.eyes(), 2, gl::DenoiseMode::Off, false);
  for (int e = 0; e < 2; ++e) {
    const auto linear = dn.readLinear(e);
    const auto display = dn.readDisplay(e);
    const auto depth = dn.readDepth(e);
    const auto& l = f.layer[e];
    for (size_t i = 0; i < linear.size(); ++i) {
      const glm::vec3 c =
          l.diffuse[i] * l.diffuseAlbedo[i] + l.specular[i] * l.specularAlbedo[i] + l.unfiltered[i];
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(linear[i][k], c[k], kHalfTol * c[k] + 1e-4f);
      const glm::u8vec3 want = displayColor(c, params.exposure);
      // One 8-bit step: the GPU converts to unorm8 with its own rounding (GL 4.5 §2.3.5.2).
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(int(display[i][k]), int(want[k]), 1) << i;
      EXPECT_EQ(display[i].a, 255);
      EXPECT_EQ(depth[i], l.depth[i]);
    }
  }
}

// The resolve: first frame passes the composite through; the second blends the
// re-projected, clamped history (both layers' motions: whole-pixel and fractional).
TEST(DenoiserPasses, ResolveMatchesCpu) {
  testing::osmesaContext();
  gl::DenoiseParams params;
  params.iterations = 1;
  gl::Denoiser dn(kW, kH, params);
  SyntheticGBuffer gbuffer(kW, kH);
  std::array<std::vector<glm::vec4>, 2> history;
  for (int t = 0; t < 2; ++t) {
    const SyntheticFrame f = tinyFrame(t);
    gbuffer.upload(f);
    dn.run(gbuffer.geometry(), f.eyes(), 2, gl::DenoiseMode::Full, t == 0);
    for (int e = 0; e < 2; ++e) {
      const std::vector<glm::vec4> color = dn.readComposited(e);
      const std::vector<glm::vec4> got = dn.readResolveHistory(e);
      const std::vector<glm::vec3> linear = dn.readLinear(e);
      for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
          const size_t i = f.index(x, y);
          const glm::vec4 want =
              testing::cpuResolve(params, f, e, x, y, color, t == 0 ? nullptr : &history[e]);
          expectNear4(got[i], want, "resolve t=" + std::to_string(t) + " " + at(e, x, y));
          for (int k = 0; k < 3; ++k) EXPECT_EQ(linear[i][k], got[i][k]) << at(e, x, y);
        }
      history[e] = got;
    }
  }
}

TEST(DenoiserPasses, ModeNamesRoundTrip) {
  for (auto m : {gl::DenoiseMode::Off, gl::DenoiseMode::Temporal, gl::DenoiseMode::Full})
    EXPECT_EQ(gl::parseDenoiseMode(gl::denoiseModeName(m)), m);
  EXPECT_THROW(gl::parseDenoiseMode("spatial"), UsageError);
}

}  // namespace
}  // namespace photovr
