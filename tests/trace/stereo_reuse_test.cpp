// Stereo path reuse (trace/stereo_reuse.h): the right eye's samples that take the left
// eye's paths beyond their first hit must give the image the right eye's own paths give, in
// expectation; where both eyes stand at one place, exactly the left eye's image.
#include "trace/stereo_reuse.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <cstdio>
#include <limits>
#include <string>
#include <tuple>
#include <vector>

#include "core/builtin_scenes.h"
#include "tests/trace/image_statistics.h"
#include "tests/trace/trace_test_util.h"
#include "trace/path_tracer.h"
#include "trace/path_stages.h"
#include "trace/wavefront.h"

namespace photovr {
namespace {

struct Fixture {
  Scene scene;
  EmbreeScene embree;
  LightSet lights;
  TraceContext ctx;
  StereoRig rig;
  explicit Fixture(const std::string& name)
      : scene(makeBuiltinScene(name)),
        embree(scene),
        lights(scene),
        ctx{scene, embree, lights, {}} {
    rig.head = poseOf(scene.cameras.at(0));
  }
  std::array<EyeCamera, 2> eyes(int w, int h, uint32_t frame) const {
    const glm::vec2 jitter = samplePosition(SamplerKind::Sobol, frame);
    return {rig.eye(Eye::Left, w, h, jitter), rig.eye(Eye::Right, w, h, jitter)};
  }
};

// Both eyes of one pt frame; 'reuse': the eye traced second reuses the first's paths (the
// eyes take turns, stereoTurnsOf). 'rightKey': the eye index the right eye's own paths
// draw their numbers for (1; 0: the left's).
std::array<EyeImage, 2> stereoFrame(const TraceContext& ctx, const std::array<EyeCamera, 2>& eyes,
                                    uint32_t frame, bool reuse, StereoPaths& paths,
                                    uint32_t rightKey = 1) {
  std::array<EyeImage, 2> out;
  const StereoTurns turns =
      stereoTurnsOf(reuse, 2, frame, paths, eyes[0], uint32_t(ctx.settings.samplesPerPixel));
  for (const int e : turns.order)
    out[e] = renderPathTraced(ctx, eyes[e], e == 0 ? 0 : rightKey, frame, {}, turns.roles[e]);
  return out;
}

// With both eyes one camera every sample of the eye traced second finds its own primary hit
// in the first: same vertex, same direction (Jacobian 1), same MIS weights, same numbers.
// The reused image must then be the first eye's to float rounding, whichever goes first, which
// checks the recorded radiance beyond x1, the re-weighted emission and the shared light samples
// term by term (the right eye's own paths, at smooth vertices, draw the left's numbers here too).
TEST(StereoReuse, EyesAtOnePlaceGiveTheLeftImage) {
  // Float rounding in the reconnection: the direction renormalised, the radiance divided and
  // re-multiplied by the throughput (~1e-6 relative), and GGX's D, which the reused term
  // evaluates at the half vector of the recorded direction where the left's sample weight
  // used the sampled one. The two half vectors differ by an angle dtheta of a few float
  // epsilons (a reflection and two normalisations: <= 16 eps), and D changes by at most
  // 2 dtheta / alpha relative (t = cos^2 + sin^2 / alpha^2 moves by 2 sin dtheta / alpha^2,
  // largest against t at sin = alpha): 32 eps / kMinAlpha = 9.4e-4 behind a roughness-0
  // vertex. Spheres' roughness-0 column reached 5.2e-4 over frames 0-9, the other pixels
  // and scenes 1e-4; a dropped factor or term is off by far more.
  constexpr float kRounding = 32.0f * std::numeric_limits<float>::epsilon() / kMinAlpha;
  for (const std::string& name : builtinSceneNames()) {
    Fixture f(name);
    f.ctx.settings.samplesPerPixel = 2;
    StereoPaths paths;
    for (const uint32_t frame :
         {0u, 1u, 2u, 3u, 4u, 5u, 6u, 7u, 8u, 9u}) {  // the left eye first, then the right
      auto eyes = f.eyes(24, 27, frame);
      eyes[1] = eyes[0];
      const auto img = stereoFrame(f.ctx, eyes, frame, true, paths, 0);
      const int first = int(frame % 2), second = 1 - first;
      ASSERT_GT(img[second].reusedPaths, 0u) << name;
      EXPECT_EQ(img[first].reusedPaths, 0u) << name;
      EXPECT_EQ(img[second].reusedOwnBounces, 0u) << name;  // the same vertex: nothing to split
      size_t compared = 0;
      for (size_t i = 0; i < img[0].color.size(); ++i) {
        const glm::vec3 a = img[first].color[i], b = img[second].color[i];
        for (int k = 0; k < 3; ++k)
          EXPECT_NEAR(a[k], b[k], kRounding * a[k] + 1e-6f)
              << name << " frame " << frame << " pixel " << i;
        ++compared;
      }
      EXPECT_EQ(compared, img[0].color.size());
    }
  }
}

// On the right eye's turn its paths draw the numbers of the left pixel that stands for each
// of its pixels, so the left eye, reusing them, keeps its own pixels' sequences. With the
// eyes at one place that is the same pixel: every path the right eye records on an odd
// frame carries the left eye's sampler for its pixel and sample (eye 0), and none its own.
TEST(StereoReuse, OnTheRightEyesTurnItsPathsDrawTheLeftPixelsNumbers) {
  Fixture f("cornell");  // every pixel a surface: every slot recorded
  f.ctx.settings.samplesPerPixel = 2;
  const uint32_t spp = 2, frame = 5;
  StereoPaths paths;
  auto eyes = f.eyes(24, 27, frame);
  eyes[1] = eyes[0];
  stereoFrame(f.ctx, eyes, frame, true, paths);
  size_t recorded = 0;
  for (uint32_t pixel = 0; pixel < 24 * 27; ++pixel)
    for (uint32_t s = 0; s < spp; ++s) {
      const size_t slot = size_t(pixel) * spp + s;
      if (paths.stamps[slot] != paths.generation) continue;
      const SampleCounters left{
          pixel, 0, frame, s, 0, f.ctx.settings.seed, spp, f.ctx.settings.sampler};
      const PathSampler want = PathSampler::make(left);
      EXPECT_EQ(paths.bounces[slot].sampler.key, want.key) << "pixel " << pixel;
      EXPECT_EQ(paths.bounces[slot].sampler.index, want.index) << "pixel " << pixel;
      ++recorded;
    }
  EXPECT_EQ(recorded, size_t(24 * 27 * spp));
}

// Each eye, reuse on against off: the same expected image region by region within Monte
// Carlo error on every built-in scene (spheres has the mirror and the glossy sweep: their
// reused samples trace their lobes' peaks themselves and reuse the rest). With reuse on an
// eye reuses the other's paths on every other frame (the eyes take turns). This bounds the
// shift's two approximations (radiance at x2 towards x1R taken as towards x1L, x1R -> x2
// visibility as x1L's) at the resolution of the test: 4 sigma of 128 frames at 32 x 36, and
// 4 sigma of the paired frames' differences (frame k draws the same numbers on and off; see
// tests/hybrid/stereo_reuse_hybrid_test.cpp), which catches a 5 % error in the reused term.
TEST(StereoReuse, EachEyeConvergesToItsOwnPathsImage) {
  constexpr int kW = 32, kH = 36, kFrames = 128;
  for (const std::string& name : builtinSceneNames()) {
    Fixture f(name);
    std::array<std::array<std::vector<std::vector<glm::vec3>>, 2>, 2> frames;  // [on][eye]
    StereoPaths paths;
    std::array<uint64_t, 2> reused{}, total{};
    for (int on = 0; on < 2; ++on)
      for (int k = 0; k < kFrames; ++k) {
        const auto eyes = f.eyes(kW, kH, uint32_t(k));
        auto img = stereoFrame(f.ctx, eyes, uint32_t(k), on == 1, paths);
        for (int e = 0; e < 2; ++e) {
          if (on) reused[e] += img[e].reusedPaths, total[e] += img[e].paths;
          frames[on][e].push_back(std::move(img[e].color));
        }
      }
    for (int e = 0; e < 2; ++e) {
      const auto off = testing::statisticsOf(frames[0][e], kW, kH);
      const auto onStats = testing::statisticsOf(frames[1][e], kW, kH);
      const double z = testing::maxRegionZ(onStats, off, testing::kRegions);
      const double paired =
          testing::maxPairedRegionZ(frames[1][e], frames[0][e], kW, kH, testing::kRegions);
      EXPECT_LT(z, testing::kMaxZ) << name << " eye " << e;
      EXPECT_LT(paired, testing::kMaxZ) << name << " eye " << e << " (paired)";
      EXPECT_GT(reused[e], 0u) << name << " eye " << e;
      std::printf("  %-8s eye %d reused %.3f of its paths, max region |z| %.2f, paired %.2f\n",
                  name.c_str(), e, double(reused[e]) / double(total[e]), z, paired);
    }
  }
}

// A square centred at 'centre' facing the wall (-Z).
glm::mat4 facingWall(const glm::vec3& centre) {
  return glm::rotate(glm::translate(glm::mat4(1.0f), centre), float(M_PI), glm::vec3(0, 1, 0));
}

// A white wall 3 m ahead and a black screen behind the eyes over x < 0 (z = 1), nothing
// else: no light comes back to the wall. A light beyond the screen along (-0.3, 0, 1) from
// the wall's point x = 1.2 m casts the screen's edge there: a sun slanted 0.3 rad towards
// +x, a lamp at (-1.2, 0, 5) (8 m from that point, the screen halfway), or a square light
// there (penumbraScene).
constexpr float kEdgeX = 1.2f;
Scene wallAndScreen() {
  Scene s;
  s.materials.push_back(testing::diffuseMaterial(glm::vec3(0.8f)));
  Material black = testing::diffuseMaterial(glm::vec3(0.0f));
  black.specularFactor = 0.0f;  // KHR_materials_specular: F0 = F90 = 0, no specular lobe
  s.materials.push_back(black);
  testing::addSquare(s, 20.0f, 0, glm::translate(glm::mat4(1.0f), {0.0f, 0.0f, -3.0f}));
  testing::addSquare(s, 20.0f, 1, facingWall({-20.0f, 0.0f, 1.0f}));  // single-sided
  return s;
}

// The wall and screen lit by a sun or a lamp: a pixel is dark (0) or lit, whatever the
// numbers, but for the edge's pixels.
Scene shadowEdgeScene(Light::Type type) {
  Scene s = wallAndScreen();
  Light light;
  light.type = type;
  light.direction = glm::normalize(glm::vec3(0.3f, 0.0f, -1.0f));      // the sun's
  light.position = {-kEdgeX, 0.0f, 5.0f};                              // the lamp's
  light.intensity = type == Light::Type::Directional ? 3.0f : 200.0f;  // the lit wall ~0.7
  s.lights.push_back(light);
  return s;
}

// Where the centre ray of pixel (x, y) of 'cam' meets the wall (z = -3).
float wallX(const EyeCamera& cam, int x, int y) {
  const glm::vec3 d = cam.rayDirection(float(x) + 0.5f, float(y) + 0.5f);
  return cam.pose.position.x + d.x * (-3.0f - cam.pose.position.z) / d.z;
}

// 'reach' pixels' width on the wall at the image centre.
float wallPixels(const EyeCamera& cam, float reach) {
  const int x = cam.width / 2, y = cam.height / 2;
  return reach * (wallX(cam, x + 1, y) - wallX(cam, x, y));
}

// Both eyes' mean luminance over 'frames' frames of 'scene' at kW x kH, the eyes taking
// turns with reuse on, or their own paths: [eye][pixel]; 'rays' adds up the rays traced.
constexpr int kWallW = 48, kWallH = 36;
std::array<std::vector<double>, 2> wallMeans(const Scene& scene, const TraceSettings& settings,
                                             int frames, uint64_t& rays) {
  const EmbreeScene embree(scene);
  const LightSet lights(scene);
  const TraceContext ctx{scene, embree, lights, settings};
  StereoRig rig;
  StereoPaths paths;
  std::array<std::vector<double>, 2> mean;
  for (auto& m : mean) m.assign(size_t(kWallW) * kWallH, 0.0);
  for (int k = 0; k < frames; ++k) {
    const glm::vec2 jitter = samplePosition(SamplerKind::Sobol, uint32_t(k));
    const std::array<EyeCamera, 2> eyes = {rig.eye(Eye::Left, kWallW, kWallH, jitter),
                                           rig.eye(Eye::Right, kWallW, kWallH, jitter)};
    const auto img = stereoFrame(ctx, eyes, uint32_t(k), settings.stereoReuse, paths);
    if (settings.stereoReuse) {  // the eye traced second reuses nearly all its samples
      EXPECT_GT(img[1 - k % 2].reusedPaths, uint64_t(kWallW * kWallH) * 9 / 10);
    }
    for (int e = 0; e < 2; ++e) {
      for (size_t i = 0; i < mean[e].size(); ++i) mean[e][i] += luminance(img[e].color[i]) / frames;
      rays += img[e].rays;
    }
  }
  return mean;
}

// How far a row's summed luminance may move when x1R's shadow is taken from x1L:
// kPartnerPixels footprints, in lit pixels. A footprint is the centre pixel's angle times
// the distance, and on this wall, which faces the eyes, a pixel is 1 / sqrt(1 + tx^2 +
// ty^2) of that wide, (tx, ty) its ray's tangents (<= the field's, 1.09 and 1.33: 1 / 1.99).
double partnerRowBound(const StereoRig& rig) {
  const FovTangents& fov = rig.leftFov;  // the right eye's mirrors it
  const double tx = std::max(fov.left, fov.right), ty = std::max(fov.up, fov.down);
  return kPartnerPixels * std::sqrt(1.0 + tx * tx + ty * ty);
}

// One eye's means 'a' against 'b' ('cam' its camera, 'lit' the lit wall's value): each
// pixel whose centre meets the wall farther than 'band' + 3 pixels from kEdgeX (beyond the
// jitter and a partner's distance) equal to float rounding (1e-5 of the lit value), and
// each row's summed difference, in lit pixels; how many pixels differ at all.
struct WallDifference {
  std::vector<double> rows;
  int pixels = 0;
};
WallDifference compareOffTheEdge(const EyeCamera& cam, const std::vector<double>& a,
                                 const std::vector<double>& b, double lit, float band,
                                 const std::string& what) {
  const float margin = band + wallPixels(cam, 3.0f);
  WallDifference d;
  d.rows.assign(kWallH, 0.0);
  for (int y = 0; y < kWallH; ++y)
    for (int x = 0; x < kWallW; ++x) {
      const size_t i = size_t(y) * kWallW + size_t(x);
      d.rows[size_t(y)] += (a[i] - b[i]) / lit;
      d.pixels += a[i] != b[i];
      if (std::abs(wallX(cam, x, y) - kEdgeX) > margin) {
        EXPECT_NEAR(a[i], b[i], 1e-5 * lit) << what << " pixel " << x << ", " << y;
      }
    }
  return d;
}

// A reused sample's NEE aims at its partner's light point, and the partner's shadow ray
// answers for it, except at the edge of a punctual light's shadow (leftShadowEdge: a row
// neighbour of the partner, aiming at the same light, got the other answer), where it
// traces its own. Each eye, reuse on (it reuses on every other frame: the eyes take turns)
// against its own paths, over 16 frames (the jitter moves the edge's pixels), for a sun
// and a lamp: away from the edge (3 pixels either side, beyond the edge's pixel and the
// partner's) every pixel is the same to float rounding (1e-5 of the lit value: a
// visibility answer taken from the wrong place, or wrongly, changes a pixel by the lit
// value, in every other frame). At the edge too: both eyes take one jitter, so x1L and x1R
// are the same offset from their pixels' centres, and the partner is the left pixel whose
// centre is nearest the right pixel's, within half a pixel along the row; an edge crossing
// the wall's rows between x1L and x1R then also lies between x1L and its neighbour a pixel
// away on that side, and the sample traces its own ray. So each row's summed luminance is
// the own paths' to rounding (1e-5 of the lit value per pixel). Without the edge test a
// row's sun edge moved by up to 0.25 and 0.06 pixels (left, right), within the earlier
// bound of kPartnerPixels footprints (partnerRowBound).
TEST(StereoReuse, TheLeftsShadowAnswerIsNotTakenAtAPunctualLightsShadowEdge) {
  constexpr int kFrames = 16;
  const StereoRig rig;
  for (const Light::Type type : {Light::Type::Directional, Light::Type::Point}) {
    const Scene scene = shadowEdgeScene(type);
    std::array<std::array<std::vector<double>, 2>, 2> mean;  // [on][eye]
    std::array<uint64_t, 2> rays{};
    for (int on = 0; on < 2; ++on) {
      TraceSettings settings;
      settings.stereoReuse = on == 1;
      mean[on] = wallMeans(scene, settings, kFrames, rays[on]);
    }
    const char* name = type == Light::Type::Directional ? "sun" : "lamp";
    EXPECT_LT(rays[1], rays[0]) << name;  // the reused samples away from the edge: no shadow ray
    for (int e = 0; e < 2; ++e) {
      const EyeCamera cam = rig.eye(e == 0 ? Eye::Left : Eye::Right, kWallW, kWallH);
      const std::vector<double>&off = mean[0][e], &on = mean[1][e];
      const double lit = *std::max_element(off.begin(), off.end());
      ASSERT_GT(lit, 0.5) << name;
      const std::string what = std::string(name) + " eye " + std::to_string(e);
      const WallDifference d = compareOffTheEdge(cam, on, off, lit, 0.0f, what);
      double worstRow = 0.0;  // in lit pixels
      for (int y = 0; y < kWallH; ++y) {
        EXPECT_EQ(off[size_t(y) * kWallW], 0.0) << what << " row " << y;  // dark at the left
        EXPECT_GT(off[size_t(y) * kWallW + kWallW - 1], 0.5 * lit) << what << " row " << y;
        EXPECT_LE(std::abs(d.rows[size_t(y)]), 1e-5 * kWallW) << what << " row " << y;
        worstRow = std::max(worstRow, std::abs(d.rows[size_t(y)]));
      }
      std::printf(
          "  %s, eye %d: the edge moved by at most %.2g pixels in a row (without the "
          "edge test the bound is %.2f)\n",
          name, e, worstRow, partnerRowBound(rig));
    }
  }
}

// A square light, 1 m wide, where the lamp of shadowEdgeScene is, black: the screen's edge
// casts a penumbra over kEdgeX +- kPenumbraHalf on the wall (the screen is halfway), 7
// pixels wide in a 48-pixel image.
constexpr float kPenumbraHalf = 0.5f;
Scene penumbraScene() {
  Scene s = wallAndScreen();
  Material light = testing::diffuseMaterial(glm::vec3(0.0f));
  light.specularFactor = 0.0f;
  light.emissiveFactor = glm::vec3(300.0f);  // the lit wall ~1
  s.materials.push_back(light);
  testing::addSquare(s, kPenumbraHalf, int(s.materials.size()) - 1,
                     facingWall({-kEdgeX, 0.0f, 5.0f}));
  return s;
}

// The same approximation at an area light's penumbra, where no test finds the edge (each
// sample aims at a point of its own on the light, and the edge for that point is a hard
// one of its own): the right sample takes V(x1L, y) for V(x1R, y) and the penumbra moves by
// at most the partners' distance. Each eye, the left's answers (the default) against every
// reused sample tracing its own shadow ray (TraceSettings::reusedOwnShadowRays), both
// drawing the same numbers, over 16 frames: outside the penumbra (its wall span, widened
// by 3 pixels for the jitter and the partners' distance) every pixel the same to float
// rounding (1e-5 of the lit value; a wrong answer changes a pixel by the lit value in every
// other frame); each row's summed luminance within the penumbra moved by at most
// kPartnerPixels footprints (partnerRowBound). The eyes' views of the wall differ by ~0.5
// pixel (its disparity's fraction): a sample's answers differ where the hard edge its
// light point casts, anywhere on the 7-pixel penumbra, runs between x1L and x1R, so ~0.5
// of a row's reused samples per frame, each moving the row's sum by 1/16 of a lit pixel;
// an eye reuses on 8 of the 16 frames: ~0.25 lit pixels a row (measured: at most 0.4),
// well within the bound's 3.
TEST(StereoReuse, TheLeftsShadowAnswerMovesAPenumbraByAtMostThePartnersDistance) {
  constexpr int kFrames = 16;
  const Scene scene = penumbraScene();
  const StereoRig rig;
  std::array<std::array<std::vector<double>, 2>, 2> mean;  // [own shadow rays][eye]
  std::array<uint64_t, 2> rays{};
  for (int own = 0; own < 2; ++own) {
    TraceSettings settings;
    settings.stereoReuse = true;
    settings.reusedOwnShadowRays = own == 1;
    mean[own] = wallMeans(scene, settings, kFrames, rays[own]);
  }
  EXPECT_LT(rays[0], rays[1]);  // the left's answers saved the reused samples' shadow rays
  int differing = 0;
  for (int e = 0; e < 2; ++e) {
    const EyeCamera cam = rig.eye(e == 0 ? Eye::Left : Eye::Right, kWallW, kWallH);
    const std::vector<double>&left = mean[0][e], &own = mean[1][e];
    const double lit = *std::max_element(own.begin(), own.end());
    ASSERT_GT(lit, 0.5);
    const std::string what = "eye " + std::to_string(e);
    const WallDifference d = compareOffTheEdge(cam, left, own, lit, kPenumbraHalf, what);
    differing += d.pixels;
    double worstRow = 0.0;  // in lit pixels
    for (int y = 0; y < kWallH; ++y) {
      EXPECT_LE(std::abs(d.rows[size_t(y)]), partnerRowBound(rig)) << what << " row " << y;
      worstRow = std::max(worstRow, std::abs(d.rows[size_t(y)]));
    }
    std::printf("  eye %d: the penumbra moved by at most %.2g pixels in a row (bound %.2f)\n", e,
                worstRow, partnerRowBound(rig));
  }
  EXPECT_GT(differing, 0);  // the approximation is at work: the test measures it
}

// The ray through the centre of the pixel of 'cam' whose sample at 'offset' sees 'point'.
glm::vec3 centreRayOf(const EyeCamera& cam, const glm::vec3& point, glm::vec2 offset) {
  const glm::mat3 toWindow = glm::inverse(glm::mat3(cam.rayDx(), cam.rayDy(), cam.rayBase()));
  const glm::vec3 w = toWindow * (point - cam.pose.position);
  const glm::vec2 centre = glm::vec2(w.x, w.y) / w.z - offset;
  return cam.rayDirection(centre.x, centre.y);
}

// A right hit 4 m in front of the left eye, on the ray of left pixel (10, 8) at the
// sample offset (0.25, 0.25), and the left eye's slots for that frame.
struct PartnerSetup {
  StereoRig rig;
  EyeCamera left, right;
  StereoPaths paths;
  SurfaceHit hit;
  static constexpr glm::vec2 kOffset{0.25f, 0.25f};
  PartnerSetup() {
    left = rig.eye(Eye::Left, 32, 24);
    right = rig.eye(Eye::Right, 32, 24);
    paths.reset(left, 1);
    const glm::vec3 dir = glm::normalize(left.rayDirection(10.75f, 8.75f));
    hit.position = left.pose.position + 4.0f * dir;
    hit.shadingNormal = hit.geometricNormal = -dir;
    hit.instance = 3;
    hit.bsdf.roughness = 1.0f;
  }
  // Records pixel (x, y)'s sample as the given instance at the hit, 'shift' away from it.
  FirstBounce* record(int x, int y, uint32_t instance, const glm::vec3& shift = glm::vec3(0.0f)) {
    FirstBounce* b = paths.slot(size_t(y) * size_t(left.width) + size_t(x), 0);
    *b = FirstBounce{};
    b->instance = instance;
    b->position = hit.position + shift;
    b->normal = hit.shadingNormal;
    return b;
  }
  const FirstBounce* partner() const {
    return findPartner(paths, hit,
                       {right.pose.position, centreRayOf(right, hit.position, kOffset)});
  }
};

// The partner is the nearest left sample when it is the same surface point (within
// kPartnerPixels footprints), and none otherwise: at an edge, where the nearest sees another
// object, not a neighbouring sample that sees this one, whose pixel's sequence the right
// pixel would then mix with its left pixel's (the next test: its own path draws that left
// pixel's numbers instead).
TEST(StereoReuse, AnEdgeWhereTheNearestLeftSampleIsAnotherSurfaceHasNoPartner) {
  PartnerSetup s;
  const float footprint = s.paths.pixelAngle * 4.0f;
  const FirstBounce* nearest = s.record(10, 8, 3, glm::vec3(0.5f * footprint, 0, 0));
  s.record(11, 8, 3);  // a neighbour on the same surface, nearer the hit
  EXPECT_EQ(s.partner(), nearest);
  s.record(10, 8, 7);  // the nearest sample now sees another object
  EXPECT_EQ(s.partner(), nullptr);
  s.record(10, 8, 3, glm::vec3(2.0f * footprint, 0, 0));  // beyond 1.5 footprints
  EXPECT_EQ(s.partner(), nullptr);
}

// The eyes take turns to go first (stereoTurnsOf): the left on even frames, the right on
// odd ones, the first recording and the second reusing. Whichever goes first, a right
// sample draws the numbers of the left pixel that stands for it (the same left pixel
// findPartner gives when it reuses), and a left sample its own pixel's: so a left pixel and
// the right pixels it stands for follow its one Sobol sequence over the frames.
TEST(StereoReuse, TheEyesTakeTurnsAndEachPairDrawsItsLeftPixelsNumbers) {
  PartnerSetup s;
  StereoPaths turnPaths;
  const StereoTurns even = stereoTurnsOf(true, 2, 4, turnPaths, s.left, 1);
  EXPECT_EQ(even.order, (std::array<int, 2>{0, 1}));
  EXPECT_EQ(even.roles[0].record, &turnPaths);
  EXPECT_EQ(even.roles[1].reuse, &turnPaths);
  const StereoTurns odd = stereoTurnsOf(true, 2, 5, turnPaths, s.left, 1);
  EXPECT_EQ(odd.order, (std::array<int, 2>{1, 0}));
  EXPECT_EQ(odd.roles[1].record, &turnPaths);
  EXPECT_EQ(odd.roles[0].reuse, &turnPaths);
  ASSERT_EQ(odd.roles[1].leftEye, &turnPaths.leftEye);
  EXPECT_EQ(odd.roles[0].leftEye, nullptr);  // the left eye keys its own numbers
  EXPECT_EQ(turnPaths.leftEye.camera.pose.position, s.left.pose.position);
  for (const bool on : {false, true}) {  // off, or one eye: left then right, no roles
    const StereoTurns none = stereoTurnsOf(on, on ? 1 : 2, 5, turnPaths, s.left, 1);
    EXPECT_EQ(none.order, (std::array<int, 2>{0, 1}));
    EXPECT_FALSE(none.roles[0].looksAcross() || none.roles[1].looksAcross());
  }
  const RightSample sample{s.right.pose.position,
                           centreRayOf(s.right, s.hit.position, PartnerSetup::kOffset)};
  const uint32_t leftPixel = 8u * uint32_t(s.left.width) + 10u;
  // The right eye goes first: no records to reuse, its left pixel's numbers.
  SampleCounters right{.pixel = 99, .eye = 1, .frame = 5, .sample = 0};
  EXPECT_EQ(partnerOrOwnNumbers(odd.roles[1], s.hit, sample, right), nullptr);
  EXPECT_EQ(right.pixel, leftPixel);
  EXPECT_EQ(right.eye, 0u);
  EXPECT_EQ(leftPixelOf(s.paths, s.hit, sample), leftPixel);  // as findPartner's
  // The left eye reuses: with no partner, its own numbers.
  SampleCounters left{.pixel = 42, .eye = 0, .frame = 5, .sample = 0};
  EXPECT_EQ(partnerOrOwnNumbers(odd.roles[0], s.hit, sample, left), nullptr);
  EXPECT_EQ(left.pixel, 42u);
  EXPECT_EQ(left.eye, 0u);
}

// A right sample without a partner draws its own path with the numbers of the left pixel
// that stands for its pixel (ownPathCounters), so that over the frames the right pixel
// keeps that one pixel's Sobol sequence whether its samples reuse or not; with no left
// pixel for it (outside the left image), its own numbers.
TEST(StereoReuse, ARightSampleWithoutPartnerDrawsItsLeftPixelsNumbers) {
  PartnerSetup s;
  s.record(10, 8, 7);  // the left pixel sees another object
  const RightSample sample{s.right.pose.position,
                           centreRayOf(s.right, s.hit.position, PartnerSetup::kOffset)};
  uint32_t leftPixel = 0;
  EXPECT_EQ(findPartner(s.paths, s.hit, sample, &leftPixel), nullptr);
  EXPECT_EQ(leftPixel, 8u * uint32_t(s.left.width) + 10u);
  const SampleCounters own{.pixel = 99, .eye = 1, .frame = 5, .sample = 0};
  const SampleCounters drawn = ownPathCounters(own, leftPixel);
  EXPECT_EQ(drawn.pixel, leftPixel);
  EXPECT_EQ(drawn.eye, 0u);  // the left eye's numbers
  EXPECT_EQ(drawn.frame, 5u);
  s.hit.position = s.right.pose.position + 4.0f * glm::vec3(1.0f, 0.0f, 0.0f);  // beside the eye
  EXPECT_EQ(findPartner(s.paths, s.hit, sample, &leftPixel), nullptr);
  EXPECT_EQ(leftPixel, kNoLeftPixel);
  EXPECT_EQ(ownPathCounters(own, leftPixel).pixel, 99u);
}

// Where eye 'cam''s ray through window position 'p' meets the floor y = kFloorY, if it does
// closer than 'range'.
constexpr float kFloorY = -0.4f;
bool floorPoint(const EyeCamera& cam, glm::vec2 p, float range, glm::vec3& point) {
  const glm::vec3 d = cam.rayDirection(p.x, p.y);
  const float t = (kFloorY - cam.pose.position.y) / d.y;
  point = cam.pose.position + t * d;
  return t > 0.0f && t < range;
}

// A floor seen at a slant: its disparity changes across a pixel, so the sample's position
// less its offset (what the partner search used to project) crosses into another left
// pixel for some offsets. The partner must be one left pixel for every offset (every frame's
// jitter), or the right pixel mixes two left pixels' stratified sequences and loses their
// stratification (atrium's right eye had ~3 % more variance). Left samples everywhere on
// the floor, at each frame's offset, as a left frame records them.
TEST(StereoReuse, ASlantedFloorKeepsOnePartnerPixelForEveryJitter) {
  StereoRig rig;
  const EyeCamera left = rig.eye(Eye::Left, 48, 36), right = rig.eye(Eye::Right, 48, 36);
  StereoPaths paths;
  std::vector<std::vector<long>> partners(size_t(right.width) * right.height);
  for (uint32_t frame = 0; frame < 16; ++frame) {
    const glm::vec2 offset = samplePosition(SamplerKind::Sobol, frame);
    paths.reset(left, 1);
    for (int y = 0; y < left.height; ++y)
      for (int x = 0; x < left.width; ++x) {
        glm::vec3 p;
        if (!floorPoint(left, glm::vec2(x + 0.5f, y + 0.5f) + offset, 1e4f, p)) continue;
        FirstBounce& b = *paths.slot(size_t(y) * size_t(left.width) + size_t(x), 0);
        b = FirstBounce{};
        b.position = p;
        b.normal = b.geometricNormal = glm::vec3(0, 1, 0);
        b.instance = 0;
      }
    for (int y = 0; y < right.height; ++y)
      for (int x = 0; x < right.width; ++x) {
        SurfaceHit hit;
        // The right eye's within 20 m: near the horizon a pixel spans kilometres of floor.
        if (!floorPoint(right, glm::vec2(x + 0.5f, y + 0.5f) + offset, 20.0f, hit.position))
          continue;
        hit.shadingNormal = hit.geometricNormal = glm::vec3(0, 1, 0);
        hit.bsdf.roughness = 1.0f;
        const RightSample sample{right.pose.position, right.rayDirection(x + 0.5f, y + 0.5f),
                                 offset};
        if (const FirstBounce* b = findPartner(paths, hit, sample))
          partners[size_t(y) * size_t(right.width) + size_t(x)].push_back(
              long(b - paths.bounces.data()));
      }
  }
  size_t pixels = 0, mixed = 0;
  for (const std::vector<long>& p : partners) {
    if (p.size() < 16) continue;  // near the horizon or the edge of the left image
    ++pixels;
    mixed += std::count(p.begin(), p.end(), p.front()) != long(p.size());
  }
  EXPECT_GT(pixels, 200u);  // the lower half of the image, less the left image's edge
  EXPECT_EQ(mixed, 0u) << "of " << pixels << " floor pixels";
}

struct Mean {
  double value = 0.0, standardError = 0.0;
};

Mean meanRadiance(const std::vector<PathResult>& results) {
  double sum = 0.0, sum2 = 0.0;
  for (const PathResult& r : results) {
    const double v = r.radiance.r;
    sum += v, sum2 += v * v;
  }
  const double n = double(results.size()), mean = sum / n;
  return {mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n)};
}

// A floor point's reused right sample against its own paths (below).
struct ReuseCase {
  Material material;
  float tiltDegrees = 0.0f;  // the left vertex's shading normal, tilted about z
  float viewDegrees = 0.0f;  // the left view, turned about the floor's normal from the right's
  Environment environment;   // default: a white furnace (a constant sky of 1)
  ReuseCase(const Material& m, float tilt, float view = 0.0f)
      : material(m), tiltDegrees(tilt), viewDegrees(view) {
    environment.type = Environment::Type::Constant;
    environment.constant = glm::vec3(1.0f);
  }
};

// PathBatcher finishes a reused sample without a path when it needs no ray
// (finishReusedSamples, the batch's together; finishReusedSample, one): its result must be
// the batched path's to the bit, and it must hand on exactly the samples whose batched
// paths traced a ray.
bool sameResult(const PathResult& a, const PathResult& b) {
  return std::memcmp(&a.radiance, &b.radiance, sizeof(glm::vec3)) == 0 &&
         std::memcmp(&a.diffuse, &b.diffuse, sizeof(glm::vec3)) == 0 &&
         a.specularAlbedo == b.specularAlbedo && a.albedo == b.albedo;
}

void expectFinishedWhereMadeAsInABatch(const TraceContext& ctx,
                                       const std::vector<PathStart>& starts,
                                       const std::vector<PathResult>& batched) {
  std::vector<PathState> paths;
  for (const PathStart& st : starts)
    paths.push_back(startPath(st.hit, st.wo, st.counters, nullptr, st.reuse));
  std::vector<PathResult> together(starts.size());
  std::vector<uint8_t> doneTogether(starts.size());
  finishReusedSamples(ctx, paths, together, doneTogether, threadScratch());
  size_t finished = 0, mismatched = 0;
  for (size_t i = 0; i < starts.size(); ++i) {
    PathResult lean;
    const bool done = finishReusedSample(ctx, starts[i].hit, starts[i].wo, *starts[i].reuse, lean);
    finished += done;
    const PathResult& b = batched[i];
    if (done != (b.rays == 0) || done != (doneTogether[i] != 0)) ++mismatched;
    if (done && (!sameResult(lean, b) || !sameResult(together[i], b))) ++mismatched;
  }
  EXPECT_EQ(mismatched, 0u);
  EXPECT_GT(finished, 0u);
}

// One floor point, seen along -wo by the right eye. The left vertex's shading normal is
// tilted by 'tiltDegrees' about z (as a normal map or a curved surface's neighbour would),
// and the left eye sees it from 'viewDegrees' away; the right vertex keeps the floor's
// normal. The right sample reusing the left path must reflect what its own paths reflect:
// the directions its hemisphere holds and the left's does not (the wedge; at 80 degrees the
// left's view is below its horizon, and the left samples nothing at all), and the peak of a
// lobe thinner than the views' angle, are its own to trace. Independent numbers (Random),
// so the standard errors hold.
Mean reusedAgainstOwn(const ReuseCase& c, Mean& own) {
  Scene s;
  s.materials.push_back(c.material);
  testing::addSquare(s, 100.0f, 0,
                     glm::rotate(glm::mat4(1.0f), -float(M_PI / 2), glm::vec3(1, 0, 0)));
  s.environment = c.environment;
  const EmbreeScene embree(s);
  const LightSet lights(s);
  const TraceContext ctx{s, embree, lights, {}};
  const glm::vec3 wo = glm::normalize(glm::vec3(0.3f, 1.0f, 0.2f));
  const glm::vec3 woLeft =
      glm::mat3(glm::rotate(glm::mat4(1.0f), glm::radians(c.viewDegrees), glm::vec3(0, 1, 0))) * wo;
  const TraceHit h = embree.intersect(wo, -wo, 0.0f, 2.0f);
  EXPECT_TRUE(h.hit);
  const SurfaceHit right = surfaceAt(s, h.instance, h.triangle, h.b1, h.b2, -wo);
  SurfaceHit left = right;
  const float a = glm::radians(c.tiltDegrees);
  if (a != 0.0f) left.shadingNormal = glm::vec3(-std::sin(a), std::cos(a), 0.0f);
  constexpr uint32_t kSamples = 40000;
  std::vector<FirstBounce> bounces(kSamples);
  std::vector<PathStart> leftStarts, reusing, owning;
  for (uint32_t i = 0; i < kSamples; ++i) {
    const SampleCounters counters{.pixel = 7, .sample = i, .kind = SamplerKind::Random};
    leftStarts.push_back({left, woLeft, counters, &bounces[i], nullptr});
    reusing.push_back({right, wo, counters, nullptr, &bounces[i]});
    SampleCounters rightEye = counters;
    rightEye.eye = 1;
    owning.push_back({right, wo, rightEye, nullptr, nullptr});
  }
  std::vector<PathResult> results(kSamples);
  continuePaths(ctx, leftStarts, results, threadScratch());
  continuePaths(ctx, owning, results, threadScratch());
  own = meanRadiance(results);
  continuePaths(ctx, reusing, results, threadScratch());
  uint32_t ownBounces = 0;
  for (const PathResult& r : results) ownBounces += r.ownBounces;
  expectFinishedWhereMadeAsInABatch(ctx, reusing, results);
  // Tilted or seen from apart, some reused samples trace the directions the left samples
  // poorly themselves.
  EXPECT_GT(ownBounces, 0u) << c.tiltDegrees << " degrees tilted, " << c.viewDegrees << " apart";
  return meanRadiance(results);
}

TEST(StereoReuse, ARightVertexTiltedFromItsPartnerTracesWhatTheLeftCannotSample) {
  for (const float tilt : {25.0f, 50.0f, 80.0f}) {
    Mean own;
    const Mean reused = reusedAgainstOwn({testing::diffuseMaterial(glm::vec3(0.8f)), tilt}, own);
    // 4 standard errors of the difference of two independent means: a false failure once
    // in ~16000 runs. Without the own-traced wedge the reused mean fell short by 1.9 %
    // (25 degrees; 5.6 standard errors: NEE's MIS weight holds most of the wedge near the
    // horizon), 12 % (50) and 84 % (80; the left samples nothing).
    const double se = std::hypot(reused.standardError, own.standardError);
    EXPECT_NEAR(reused.value, own.value, 4.0 * se) << tilt << " degrees";
    std::printf("  tilt %2.0f: reused %.4f, own %.4f (se %.4f)\n", tilt, reused.value, own.value,
                se);
  }
}

// A glossy metal (bronze, roughness 0.35, as atrium's capitals) whose partner's normal is
// 15 degrees off: the right lobe's peak sits ~30 degrees from the left's, where the left pdf
// is thin. The reused estimate must stay nearly as tight as the own one (the split hands
// those directions to the right sample's own path). Over the reused region the weight is at
// most kReusePdfRatio = 2 times the own sample's, so its second moment is at most 2x the
// own's; the own region adds at most 1x; and the two terms draw the same numbers, so they
// correlate: 2.5x the own standard error (6x the variance) bounds that with room. Measured:
// 1.9x; reusing every direction the left covers, as before the split: 10x (and 1.5 % low,
// the heavy tail's missing spikes).
TEST(StereoReuse, AGlossyRightVertexKeepsItsOwnNoiseWhereTheLeftLobeIsThin) {
  Material bronze = testing::diffuseMaterial(glm::vec3(0.8f, 0.5f, 0.28f));
  bronze.metallicFactor = 1.0f;
  bronze.roughnessFactor = 0.35f;
  Mean own;
  const Mean reused = reusedAgainstOwn({bronze, 15.0f}, own);
  const double se = std::hypot(reused.standardError, own.standardError);
  EXPECT_NEAR(reused.value, own.value, 4.0 * se);
  EXPECT_LT(reused.standardError, 2.5 * own.standardError);
  std::printf("  bronze: reused %.4f (se %.4f), own %.4f (se %.4f)\n", reused.value,
              reused.standardError, own.value, own.standardError);
}

// A sky of 8 x 4 cells, alternately 2 and 0.2: what a thin lobe reflects changes with the
// view, so a reused sample that kept the left's reflection would show it.
Environment checkerSky() {
  Environment e;
  e.type = Environment::Type::Map;
  e.width = 64;
  e.height = 32;
  for (int y = 0; y < e.height; ++y)
    for (int x = 0; x < e.width; ++x)
      e.pixels.push_back(glm::vec3((x / 8 + y / 8) % 2 ? 2.0f : 0.2f));
  return e;
}

// Smooth vertices reuse too (ReuseSplit without 'whole'; in frames a mirror-like one has no
// partner, AMirrorLikeVertex... below): seen from 10 degrees apart (the
// eyes' angle at ~0.35 m), a mirror's peak, a smooth coat's peak over its diffuse base and
// a glossy metal's lobe (alpha 0.04, under the views' 0.17 rad) are not where the left's
// are, and must be the right sample's own to trace, while the rest is reused. Compared with
// the right eye's own paths under a checkered sky (what a thin lobe reflects changes with
// the view): the means within 4 standard errors of the difference, as above, plus 1e-4 of
// the mean for float rounding where both are nearly noiseless (the mirror); the reused
// estimate's standard error within 2.5x the own one's, as for the bronze vertex, plus that
// rounding. Reused 'whole' (every direction the left's, as for a rough vertex) the means
// still agree, as the reused term is unbiased wherever the left samples, but its weight
// f / pdf_L spikes: standard errors 1000x (mirror), 5.5x (coat) and 1.8x (glossy) the own.
TEST(StereoReuse, ASmoothRightVertexSeenFromApartTracesItsOwnPeak) {
  Material mirror = testing::diffuseMaterial(glm::vec3(0.9f, 0.6f, 0.4f));
  mirror.metallicFactor = 1.0f;
  mirror.roughnessFactor = 0.0f;
  Material coated = testing::diffuseMaterial(glm::vec3(0.8f));
  coated.roughnessFactor = 0.0f;
  Material glossy = mirror;
  glossy.roughnessFactor = 0.2f;
  for (const auto& [name, material] : {std::pair<const char*, Material>{"mirror", mirror},
                                       {"coated", coated},
                                       {"glossy", glossy}}) {
    ReuseCase c(material, 0.0f, 10.0f);
    c.environment = checkerSky();
    Mean own;
    const Mean reused = reusedAgainstOwn(c, own);
    const double se = std::hypot(reused.standardError, own.standardError);
    EXPECT_NEAR(reused.value, own.value, 4.0 * se + 1e-4 * own.value) << name;
    EXPECT_LT(reused.standardError, 2.5 * own.standardError + 1e-4 * own.value) << name;
    std::printf("  %-6s: reused %.4f (se %.4f), own %.4f (se %.4f)\n", name, reused.value,
                reused.standardError, own.value, own.standardError);
  }
}

// A mirror-like vertex (mirrorLike: a smooth metal) has no partner and traces its own path
// with the left pixel's numbers; a smooth dielectric, whose diffuse base carries its noise,
// and a metal at kReuseMinRoughness keep theirs. Why, measured with the split (as
// ASmoothRightVertex... above, under the checkered sky, from 0.6 degrees apart: the eyes'
// angle at ~6 m): a mirror's reused standard error is 5-6x its own paths' (its lobe's peak
// is its own to trace anyway, and the split's boundary a few alphas from it adds noise its
// own path does not have), a smooth dielectric's 1.0x.
TEST(StereoReuse, AMirrorLikeVertexHasNoPartnerAndDrawsItsLeftPixelsNumbers) {
  PartnerSetup s;
  const FirstBounce* recorded = s.record(10, 8, 3);
  const uint32_t leftPixel = 8u * uint32_t(s.left.width) + 10u;
  const RightSample sample{s.right.pose.position,
                           centreRayOf(s.right, s.hit.position, PartnerSetup::kOffset)};
  BsdfParams mirror;
  mirror.baseColor = glm::vec3(0.9f, 0.6f, 0.4f);
  mirror.metallic = 1.0f;
  mirror.roughness = 0.0f;
  BsdfParams smoothDielectric = mirror, halfMetal = mirror, glossy = mirror;
  smoothDielectric.metallic = 0.0f;
  halfMetal.metallic = 0.5f;  // F0's luminance 0.34 against the base's 0.33: mirror-like
  glossy.roughness = kReuseMinRoughness;
  for (const auto& [name, bsdf, reused] :
       {std::tuple<const char*, BsdfParams, bool>{"mirror", mirror, false},
        {"half metal", halfMetal, false},
        {"smooth dielectric", smoothDielectric, true},
        {"glossy metal", glossy, true}}) {
    s.hit.bsdf = bsdf;
    EXPECT_EQ(mirrorLike(bsdf), !reused) << name;
    uint32_t pixel = kNoLeftPixel;
    EXPECT_EQ(findPartner(s.paths, s.hit, sample, &pixel), reused ? recorded : nullptr) << name;
    EXPECT_EQ(pixel, leftPixel) << name;  // its own path draws that pixel's numbers
  }
}

// Through the whole stereo frame (pt): a mirror floor under a sky of 1, seen from 1.6 m by
// eyes 64 mm apart (the views 0.6-1.2 degrees apart on the floor), the same jitter every
// frame and independent numbers (the random sampler). Each eye's per-pixel variance over
// the frames, summed over the image, reuse on against off: the same distribution (the
// reusing eye's mirror pixels trace their own paths, the left eye's with its own numbers,
// so its ratio is 1 exactly), so the ratio is 1 within the estimate's error (a few % at 64
// frames over ~700 mirror pixels; measured 1.02; 1.25 holds it with room). With the split
// at the mirror (mirrorLike false) it was 9.8x and 10.5x.
TEST(StereoReuse, AMirrorKeepsItsOwnPathsNoiseInTheReusingEye) {
  constexpr int kW = 32, kH = 24, kFrames = 64;
  Scene scene;
  Material mirror = testing::diffuseMaterial(glm::vec3(0.9f, 0.6f, 0.4f));
  mirror.metallicFactor = 1.0f;
  mirror.roughnessFactor = 0.0f;
  scene.materials.push_back(mirror);
  testing::addSquare(scene, 100.0f, 0,
                     glm::rotate(glm::mat4(1.0f), -float(M_PI / 2), glm::vec3(1, 0, 0)));
  scene.environment.type = Environment::Type::Constant;
  scene.environment.constant = glm::vec3(1.0f);
  const EmbreeScene embree(scene);
  const LightSet lights(scene);
  TraceContext ctx{scene, embree, lights, {}};
  ctx.settings.sampler = SamplerKind::Random;
  StereoRig rig;
  rig.head = lookAt({0.0f, 1.6f, 0.0f}, {0.0f, 0.0f, -2.5f});
  const std::array<EyeCamera, 2> eyes{rig.eye(Eye::Left, kW, kH), rig.eye(Eye::Right, kW, kH)};
  std::array<std::array<double, 2>, 2> variance{};  // [on][eye], summed over the pixels
  uint64_t reused = 0;
  StereoPaths paths;
  for (int on = 0; on < 2; ++on) {
    std::array<std::vector<double>, 2> sum, sum2;
    for (int e = 0; e < 2; ++e) sum[e].assign(kW * kH, 0.0), sum2[e].assign(kW * kH, 0.0);
    for (uint32_t k = 0; k < kFrames; ++k) {
      const auto img = stereoFrame(ctx, eyes, k, on == 1, paths);
      for (int e = 0; e < 2; ++e) {
        if (on) reused += img[e].reusedPaths;
        for (size_t i = 0; i < img[e].color.size(); ++i) {
          const double v = luminance(img[e].color[i]);
          sum[e][i] += v, sum2[e][i] += v * v;
        }
      }
    }
    for (int e = 0; e < 2; ++e)
      for (size_t i = 0; i < sum[e].size(); ++i) {
        const double mean = sum[e][i] / kFrames;
        variance[on][e] += (sum2[e][i] / kFrames - mean * mean) * kFrames / (kFrames - 1);
      }
  }
  EXPECT_EQ(reused, 0u);  // every surface pixel is the mirror
  for (int e = 0; e < 2; ++e) {
    const double ratio = variance[1][e] / variance[0][e];
    EXPECT_GT(variance[0][e], 0.0);
    EXPECT_LT(ratio, 1.25) << "eye " << e;
    EXPECT_GT(ratio, 1.0 / 1.25) << "eye " << e;
    std::printf("  eye %d: summed variance on / off %.3f\n", e, ratio);
  }
}

}  // namespace
}  // namespace photovr
