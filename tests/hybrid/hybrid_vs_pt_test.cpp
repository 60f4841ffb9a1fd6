// The hybrid's claim, tested: primaries from the G-buffer continued by Embree converge to
// the same image as pure path tracing. Both renderers use the same per-frame jitter, so
// with independent seeds their per-pixel means differ only by Monte Carlo noise.
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "core/builtin_scenes.h"
#include "core/error_metrics.h"
#include "core/mesh_gen.h"
#include "hybrid/hybrid_renderer.h"
#include "tests/gl/gl_test_util.h"
#include "tests/trace/reference_bsdf.h"

namespace photovr {
namespace {

Material material(glm::vec3 color, float metallic, float roughness) {
  return testing::plainMaterial(color, metallic, roughness);
}

void add(Scene& s, Mesh mesh, const Material& m) {
  s.materials.push_back(m);
  mesh.material = int(s.materials.size()) - 1;
  s.meshes.push_back(std::move(mesh));
  s.instances.push_back({int(s.meshes.size()) - 1, glm::mat4(1.0f), glm::mat4(1.0f), "m"});
}

void addCamera(Scene& s, glm::vec3 from, glm::vec3 at, float yfovDegrees) {
  Camera c;
  const Pose p = lookAt(from, at);
  c.position = p.position;
  c.orientation = p.orientation;
  c.yfov = glm::radians(yfovDegrees);
  s.cameras.push_back(c);
}

// Thin geometry and sharp silhouettes: 3 mm slats in front of a lit backdrop.
// A back wall and a floor under a point light and a grey sky, seen from 3 m.
Scene lightRoom() {
  Scene s;
  add(s, makeQuad({-3, 0, -2}, {6, 0, 0}, {0, 3, 0}), material(glm::vec3(0.8f), 0, 0.8f));
  add(s, makeQuad({-3, 0, 2}, {6, 0, 0}, {0, 0, -4}), material(glm::vec3(0.5f), 0, 0.5f));
  Light l;
  l.position = {1, 2.5f, 1};
  l.intensity = 6.0f;
  s.lights.push_back(l);
  s.environment.type = Environment::Type::Constant;
  s.environment.constant = glm::vec3(0.3f);
  addCamera(s, {0, 1, 2}, {0, 1, -1}, 60);
  return s;
}

Scene thinScene() {
  Scene s = lightRoom();
  for (int i = 0; i < 12; ++i) {
    const float x = -1.1f + 0.2f * i;
    add(s, makeBox({x, 0, -1}, {x + 0.003f, 2, -0.997f}), material({0.9f, 0.3f, 0.1f}, 1, 0.3f));
  }
  return s;
}

// A roughness-0 mirror facing a diffuse sphere under a small area light.
Scene mirrorScene() {
  Scene s;
  add(s, makeQuad({-3, 0, 3}, {6, 0, 0}, {0, 0, -6}), material(glm::vec3(0.6f), 0, 1));
  add(s, makeQuad({-1.5f, 0, -1.5f}, {3, 0, 0}, {0, 2, 0}), material(glm::vec3(0.95f), 1, 0));
  Mesh sphere = makeUvSphere(0.4f, 32, 16);
  transformMesh(sphere, glm::translate(glm::mat4(1.0f), {0.3f, 0.4f, 0}));
  add(s, sphere, material({0.2f, 0.5f, 0.9f}, 0, 0.6f));
  Material light = material(glm::vec3(0), 0, 1);
  light.emissiveFactor = glm::vec3(20.0f);
  add(s, makeQuad({-0.25f, 2.5f, 0.75f}, {0.5f, 0, 0}, {0, 0, -0.5f}), light);
  s.environment.type = Environment::Type::Constant;
  s.environment.constant = glm::vec3(0.1f);
  addCamera(s, {-0.8f, 1.0f, 2.5f}, {0, 0.7f, -1.5f}, 60);
  return s;
}

// An emitter seen directly in part of the image: a panel facing the camera from 3 m, inside
// one block of the region test below (block column 1, row 1 of 4 x 3: pixel columns 5-9 and
// rows 6-11 of 20 x 18 cover x in [-0.96, 0], y in [0.42, 1.58] on the plane z = -1; the
// panel keeps 0.1 m, half a pixel, inside). None of the other scenes shows emission at a
// primary hit: cornell's ceiling light is 57 degrees above the view axis (half-fov 27.5),
// mirror's is out of view.
constexpr float kPanelEmission = 4.0f;
constexpr glm::vec2 kPanelMin{-0.85f, 0.55f}, kPanelMax{-0.1f, 1.45f};
constexpr float kPanelZ = -1.0f;

Scene lampScene() {
  Scene s = lightRoom();
  // Dark, so its pixels are mostly emission, but not black: they carry noise of their own.
  Material panel = material(glm::vec3(0.05f), 0, 0.5f);
  panel.emissiveFactor = glm::vec3(kPanelEmission);
  const glm::vec2 size = kPanelMax - kPanelMin;  // edges +x, +y: the front faces +z
  add(s, makeQuad({kPanelMin, kPanelZ}, {size.x, 0, 0}, {0, size.y, 0}), panel);
  return s;
}

// Glass (KHR_materials_transmission): a solid absorbing sphere and a rough thin-walled
// pane in the lit room: the hybrid continues refracted paths from its rasterized hits, and
// the sphere's back faces (single-sided, but where light leaves the volume) are seen
// through its front.
Scene glassScene() {
  Scene s = lightRoom();
  Material solid = material(glm::vec3(1.0f), 0, 0);
  solid.transmissionFactor = 1.0f;
  solid.thicknessFactor = 0.8f;
  solid.attenuationColor = {0.9f, 0.6f, 0.4f};
  solid.attenuationDistance = 0.5f;
  Mesh sphere = makeUvSphere(0.4f, 48, 24);
  transformMesh(sphere, glm::translate(glm::mat4(1.0f), {-0.4f, 0.8f, -0.5f}));
  add(s, sphere, solid);
  Material pane = material(glm::vec3(0.7f, 0.9f, 0.8f), 0, 0.3f);
  pane.transmissionFactor = 0.9f;
  add(s, makeQuad({0.1f, 0.3f, -0.3f}, {0.9f, 0, 0}, {0, 1.2f, 0}), pane);
  return s;
}

// alpha BLEND (stochastic coverage): a dark tinted pane of alpha 0.3 before the lit wall; the
// G-buffer's per-pixel coin and Embree's per-ray coin must agree in distribution. With the
// G-buffer's coin removed (the pane opaque there) the worst region reads |z| = 23 at alpha 0.5;
// alpha 0.3, not 0.5, so that a coin compared the wrong way (covering 0.7) fails too (16).
Scene blendScene() {
  Scene s = lightRoom();
  Material pane = material(glm::vec3(0.05f, 0.15f, 0.3f), 0, 0.4f);
  pane.alphaMode = AlphaMode::Blend;
  pane.baseColorFactor.a = 0.3f;
  pane.doubleSided = true;
  add(s, makeQuad({-0.9f, 0.4f, -0.5f}, {1.5f, 0, 0}, {0, 1.1f, 0}), pane);
  return s;
}

// A glossy metal wall (roughness 0.25) beside a floor, under a sun that it throws onto the
// floor in front of it, nothing else: the sun's caustic, which the hybrid below light-traces
// (trace/caustics.h) and pure path tracing finds by its bounces (the wall's lobe is wide
// enough for that in 32 frames).
Scene causticScene() {
  Scene s;
  add(s, makeQuad({-10, 0, 10}, {20, 0, 0}, {0, 0, -20}), material(glm::vec3(0.5f), 0, 1));
  add(s, makeQuad({-1, 0, 3}, {0, 0, -6}, {0, 2, 0}), material({0.9f, 0.6f, 0.3f}, 1, 0.25f));
  Light sun;
  sun.type = Light::Type::Directional;
  sun.direction = glm::normalize(glm::vec3(-1.0f, -0.6f, -0.2f));
  sun.intensity = 3.0f;
  s.lights.push_back(sun);
  s.environment.type = Environment::Type::Constant;  // light in the wall's shadow too
  s.environment.constant = glm::vec3(0.2f);
  addCamera(s, {0.5f, 3.0f, 2.5f}, {0.3f, 0.0f, -0.5f}, 50);
  return s;
}

Scene sceneNamed(const std::string& name) {
  if (name == "caustic") return causticScene();
  if (name == "blend") return blendScene();
  if (name == "glass") return glassScene();
  if (name == "thin") return thinScene();
  if (name == "mirror") return mirrorScene();
  if (name == "lamp") return lampScene();
  return makeBuiltinScene(name);
}

double lum(const glm::dvec3& c) {
  return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
}

// Per-pixel running sums of a mono eye's colour over frames.
struct FrameStats {
  std::vector<glm::dvec3> sum;
  int frames = 0;
  void add(const EyeImage& img) {
    sum.resize(img.color.size());
    for (size_t i = 0; i < img.color.size(); ++i) sum[i] += glm::dvec3(img.color[i]);
    ++frames;
  }
};

// Per pixel, over frames: sums of d = lum(hybrid) - lum(pt) and of d^2. Both renderers trace
// the frame's jittered pixel position, so d holds the two seeds' Monte Carlo noise and none
// of the jitter's variation (which the difference cancels); frames are independent.
struct PairedStats {
  std::vector<double> sum, sum2;
  double ptTotal = 0.0;
  int frames = 0;
  void add(const EyeImage& hybrid, const EyeImage& pt) {
    sum.resize(pt.color.size());
    sum2.resize(pt.color.size());
    for (size_t i = 0; i < pt.color.size(); ++i) {
      const double d = lum(hybrid.color[i]) - lum(pt.color[i]);
      sum[i] += d;
      sum2[i] += d * d;
      ptTotal += lum(pt.color[i]);
    }
    ++frames;
  }
  double mean(size_t i) const { return sum[i] / frames; }
  // Unbiased variance of d over the frames, over the frame count: the variance of mean(i).
  double varianceOfMean(size_t i) const {
    const double m = mean(i);
    return std::max(0.0, sum2[i] - frames * m * m) / (frames - 1) / frames;
  }
};

constexpr int kWidth = 20, kHeight = 18;

EyeCamera monoCamera(const Scene& s, uint32_t frame, SamplerKind kind = SamplerKind::Sobol) {
  EyeCamera c;
  c.pose = poseOf(s.cameras.at(0));
  c.fov = FovTangents::symmetric(s.cameras[0].yfov, float(kWidth) / kHeight);
  c.width = kWidth;
  c.height = kHeight;
  c.jitter = samplePosition(kind, frame);
  return c;
}

// What storePixel added to the two lobes at a primary hit: the surface's emission. Zero
// for background pixels (depth 0), whose colour is the sky.
glm::vec3 emittedPart(const EyeImage& img, size_t i) {
  if (img.depth[i] == 0.0f) return glm::vec3(0.0f);
  return img.color[i] -
         (img.diffuse[i] * img.diffuseAlbedo[i] + img.specular[i] * img.specularAlbedo[i]);
}

// The hybrid image as it would be with its primary hits' emission scaled by 'scale'.
EyeImage withEmissionScaled(EyeImage img, float scale) {
  for (size_t i = 0; i < img.color.size(); ++i)
    img.color[i] += (scale - 1.0f) * emittedPart(img, i);
  return img;
}

struct Paired {
  PairedStats stats;
  PairedStats emissionBiased;  // the hybrid's primary-hit emission 2 % too bright
};

// 'caustics': the hybrid light-traces directional lights' caustics, pure path tracing not.
Paired renderBoth(const Scene& scene, int frames, bool caustics = false) {
  testing::osmesaContext();
  TraceSettings hs;
  hs.seed = 1;
  hs.caustics = caustics;
  HybridRenderer renderer(scene, kWidth, kHeight, hs);
  TraceSettings ps = hs;
  ps.seed = 2;  // independent noise
  ps.caustics = false;
  const TraceContext& hc = renderer.traceContext();
  const TraceContext pc{hc.scene, hc.embree, hc.lights, ps};
  Paired p;
  for (int f = 0; f < frames; ++f) {
    const EyeCamera cam = monoCamera(scene, uint32_t(f));
    const EyeImage hybrid = renderer.render({cam, cam}, 1, uint32_t(f), nullptr)[0];
    const EyeImage pt = renderPathTraced(pc, cam, 0, uint32_t(f));
    p.stats.add(hybrid, pt);
    p.emissionBiased.add(withEmissionScaled(hybrid, 1.02f), pt);
  }
  return p;
}

// The regions tested: 4 x 3 blocks (5 x 6 pixels at 20 x 18), so that biases of opposite
// sign in different parts of the image cannot cancel, and the whole image, the most
// sensitive to a bias everywhere.
struct Region {
  int x0, y0, x1, y1;
};

std::vector<Region> testedRegions() {
  constexpr int kBlocksX = 4, kBlocksY = 3;
  std::vector<Region> r;
  for (int by = 0; by < kBlocksY; ++by)
    for (int bx = 0; bx < kBlocksX; ++bx)
      r.push_back({bx * kWidth / kBlocksX, by * kHeight / kBlocksY, (bx + 1) * kWidth / kBlocksX,
                   (by + 1) * kHeight / kBlocksY});
  r.push_back({0, 0, kWidth, kHeight});
  return r;
}

struct RegionZ {
  double diff = 0.0, variance = 0.0;
  double z() const { return diff / std::sqrt(variance); }
};

// Z = sum of the region's per-pixel mean differences / its standard error. Pixels are
// independent (the random numbers are keyed by pixel), so the variances add.
RegionZ regionZ(const PairedStats& p, const Region& r) {
  RegionZ z;
  for (int y = r.y0; y < r.y1; ++y)
    for (int x = r.x0; x < r.x1; ++x) {
      const size_t i = size_t(y) * kWidth + x;
      z.diff += p.mean(i);
      z.variance += p.varianceOfMean(i);
    }
  return z;
}

// The z beyond which a region fails: two-sided, Bonferroni over the regions. The family-wise
// false-failure rate is P(|Z| > 4) = 6.3e-5, the rate of the whole-image test this replaces
// (Z ~ N(0, 1) by the CLT over a block's 30 pixels x 32 frames; a firefly inflates its own
// variance estimate with it, which keeps a self-normalised Z bounded, not larger).
double criticalZ(size_t regions) {
  const double perRegion = std::erfc(4.0 / std::sqrt(2.0)) / double(regions);
  double lo = 0.0, hi = 40.0;  // erfc(z / sqrt 2) = P(|Z| > z) falls with z: bisect
  for (int k = 0; k < 100; ++k) {
    const double mid = 0.5 * (lo + hi);
    (std::erfc(mid / std::sqrt(2.0)) > perRegion ? lo : hi) = mid;
  }
  return hi;
}

double maxAbsZ(const PairedStats& p) {
  double worst = 0.0;
  for (const Region& r : testedRegions()) worst = std::max(worst, std::abs(regionZ(p, r).z()));
  return worst;
}

class HybridVsPt : public ::testing::TestWithParam<const char*> {};

TEST_P(HybridVsPt, EveryRegionsMeansAgreeWithinTheirMonteCarloError) {
  const Scene scene = sceneNamed(GetParam());
  const PairedStats p = renderBoth(scene, 32, std::string(GetParam()) == "caustic").stats;
  ASSERT_GT(p.ptTotal, 0.0) << GetParam() << " is black";
  const std::vector<Region> regions = testedRegions();
  const double limit = criticalZ(regions.size());  // 4.57 for 13 regions
  for (const Region& r : regions) {
    const RegionZ z = regionZ(p, r);
    // A zero variance estimate would pass any difference (and it means the region holds no
    // noise at all, which no block of these scenes does): it fails, as a non-finite one does.
    ASSERT_TRUE(std::isfinite(z.diff) && std::isfinite(z.variance) && z.variance > 0.0)
        << GetParam() << " region " << r.x0 << "," << r.y0 << ": variance " << z.variance;
    EXPECT_LT(std::abs(z.z()), limit)
        << GetParam() << " region " << r.x0 << "," << r.y0 << "-" << r.x1 << "," << r.y1
        << ": mean difference " << z.diff << ", sigma " << std::sqrt(z.variance);
  }
  RecordProperty("max_abs_z", std::to_string(maxAbsZ(p)));
}

INSTANTIATE_TEST_SUITE_P(Scenes, HybridVsPt,
                         ::testing::Values("cornell", "spheres", "atrium", "thin", "mirror", "lamp",
                                           "glass", "blend", "caustic"));

// The region test's power: the lamp panel's emission 2 % too bright in the hybrid alone
// (what a bias in the hybrid's own primary hits, hybrid/hit_rebuild.cpp or
// hybrid/hybrid_tracer.cpp, does) fails the panel's block: its ~18 panel pixels gain
// 0.02 x 4 each, 1.3 in all (measured), against the block's standard error of 0.09: Z = 14.
TEST(HybridVsPtPower, ATwoPercentEmissionBiasInOneRegionFails) {
  const Paired p = renderBoth(lampScene(), 32);
  const double limit = criticalZ(testedRegions().size());
  EXPECT_LT(maxAbsZ(p.stats), limit);
  EXPECT_GT(maxAbsZ(p.emissionBiased), limit);
  RecordProperty("max_abs_z_emission_biased", std::to_string(maxAbsZ(p.emissionBiased)));
}

// Hybrid and pt share the code that adds the primary hit's emission (storePixel), so no
// comparison of the two can see a bias there: this checks it against the material. Every
// pixel whose ray meets the lamp panel holds exactly kPanelEmission beside its lobes; every
// other surface pixel none.
void expectEmissionOfThePanel(const EyeImage& img, const EyeCamera& cam, const char* mode) {
  // 1 mm of the panel's edges (1/190 of a pixel there) is left out: a ray that close may
  // round to either side.
  constexpr float kMargin = 1e-3f;
  int inside = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const glm::vec3 dir = cam.pixelRay(x, y);
      const glm::vec3 p = cam.pose.position + dir * ((kPanelZ - cam.pose.position.z) / dir.z);
      const glm::vec2 lo = glm::vec2(p) - kPanelMin, hi = kPanelMax - glm::vec2(p);
      const float edge = std::min(std::min(lo.x, lo.y), std::min(hi.x, hi.y));
      if (std::abs(edge) < kMargin) continue;
      const size_t i = img.index(x, y);
      const float expected = edge > 0.0f ? kPanelEmission : 0.0f;
      inside += edge > 0.0f;
      // colour = lobes + emission, less the lobes rebuilt from their albedo-divided AOVs:
      // a few float roundings of the largest term, ~1e-6 relative; 1e-5 leaves margin and
      // a 2 % bias is 2e-2.
      const float tolerance = 1e-5f * std::max(img.color[i].g, kPanelEmission);
      EXPECT_NEAR(emittedPart(img, i).g, expected, tolerance) << mode << " " << x << "," << y;
    }
  EXPECT_GT(inside, 10) << mode;  // ~18 pixels see the panel
}

TEST(HybridEmission, ADirectlySeenEmitterShowsExactlyItsEmittedRadiance) {
  const Scene scene = lampScene();
  testing::osmesaContext();
  HybridRenderer renderer(scene, kWidth, kHeight, TraceSettings{});
  const EyeCamera cam = monoCamera(scene, 0);
  expectEmissionOfThePanel(renderer.render({cam, cam}, 1, 0, nullptr)[0], cam, "hybrid");
  expectEmissionOfThePanel(renderPathTraced(renderer.traceContext(), cam, 0, 0), cam, "pt");
}

std::vector<glm::vec3> meanImage(const FrameStats& s) {
  std::vector<glm::vec3> out(s.sum.size());
  for (size_t i = 0; i < out.size(); ++i) out[i] = glm::vec3(s.sum[i] / double(s.frames));
  return out;
}

// relMSE of the mean of the first N frames of one pixel sequence, N = 4, 16, 64, mean
// over 'seeds' seeds: the hybrid's frames or pure path tracing's with the same settings.
std::vector<double> convergence(const Scene& scene, const std::vector<glm::vec3>& ref,
                                HybridRenderer& renderer, bool hybrid, int seeds) {
  std::vector<double> e(3, 0.0);
  const TraceContext& hc = renderer.traceContext();
  for (int seed = 0; seed < seeds; ++seed) {
    TraceSettings ts = hc.settings;
    ts.seed = uint32_t(1 + 2 * seed + (hybrid ? 0 : 1));
    renderer.setSeed(ts.seed);
    const TraceContext pc{hc.scene, hc.embree, hc.lights, ts};
    FrameStats stats;
    int k = 0;
    for (int f = 0; f < 64; ++f) {
      const EyeCamera cam = monoCamera(scene, uint32_t(f), ts.sampler);
      stats.add(hybrid ? renderer.render({cam, cam}, 1, uint32_t(f), nullptr)[0]
                       : renderPathTraced(pc, cam, 0, uint32_t(f)));
      if (f == 3 || f == 15 || f == 63) e[k++] += relMse(meanImage(stats), ref) / seeds;
    }
  }
  return e;
}

class HybridConvergence : public ::testing::TestWithParam<const char*> {};

TEST_P(HybridConvergence, ErrorAgainstAConvergedReferenceFallsLikeOneOverN) {
  const Scene scene = sceneNamed(GetParam());
  // Reference: 64 frames x 32 spp = 2048 samples per pixel of pure path tracing.
  const EmbreeScene embree(scene);
  const LightSet lights(scene);
  TraceSettings rs;
  rs.samplesPerPixel = 32;
  rs.seed = 99;
  const TraceContext rc{scene, embree, lights, rs};
  FrameStats reference;
  for (int f = 0; f < 64; ++f)
    reference.add(renderPathTraced(rc, monoCamera(scene, uint32_t(f)), 0, uint32_t(f)));
  const std::vector<glm::vec3> ref = meanImage(reference);
  testing::osmesaContext();
  // Heavy-tailed scenes average relMSE over independent seeds: one firefly among the first
  // 4 frames otherwise decides relMSE(4) (spheres, pt, one seed: 2.48, 0.16, 0.014; the
  // Cornell box's metal block, hybrid, random sampler: 0.042, 0.042, 0.018).
  const std::string name = GetParam();
  const int seeds = name == "spheres" || name == "cornell" ? 4 : 1;
  double random64[2] = {0.0, 0.0};  // the random sampler's relMSE(64), pt and hybrid
  for (SamplerKind kind : {SamplerKind::Random, SamplerKind::Sobol}) {
    TraceSettings settings;
    settings.sampler = kind;
    HybridRenderer renderer(scene, kWidth, kHeight, settings);
    for (bool hybrid : {true, false}) {
      const std::vector<double> e = convergence(scene, ref, renderer, hybrid, seeds);
      const std::string what =
          std::string(GetParam()) + " " + (hybrid ? "hybrid " : "pt ") + samplerName(kind);
      RecordProperty(what + " relmse_4_16_64", std::to_string(e[0]) + " " + std::to_string(e[1]) +
                                                   " " + std::to_string(e[2]));
      EXPECT_LT(e[1], e[0]) << what;
      EXPECT_LT(e[2], e[1]) << what;
      if (kind == SamplerKind::Sobol) {
        // The stratified sequence must not lose to independent numbers at N = 64 (issue
        // 18): measured 0.3 .. 1.07 of the random sampler's relMSE over the 10 rows; the
        // Cornell box, whose error is in the later bounces, gains least (1.14x at 64 spp
        // in bench_sampler's 96x96 frames), and the relMSE of 360 pixels over 4 seeds
        // varies by ~15 %, hence 1.25. A sequence whose draws were correlated or whose
        // index did not span the frames does worse than random, or stops converging
        // (the two assertions above).
        EXPECT_LT(e[2], 1.25 * random64[hybrid]) << what;
        continue;
      }
      random64[hybrid] = e[2];
      // Ideal 1/16 from N = 4 to 64 for independent samples. relMSE of a 360-pixel image is
      // itself noisy (a few fireflies dominate it), so the band is a factor 2.5 either way;
      // the reference's own error (1/32 of the N = 64 image's variance) flattens the curve
      // slightly.
      EXPECT_LT(e[2], e[0] / 16.0 * 2.5) << what;
      EXPECT_GT(e[2], e[0] / 16.0 / 2.5) << what;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, HybridConvergence,
                         ::testing::Values("cornell", "spheres", "atrium", "thin", "mirror"));

}  // namespace
}  // namespace photovr

namespace photovr {
namespace {

// f cos / r^2 x I at the floor point a ray meets, from the independent BRDF of
// tests/trace/reference_bsdf.h, in double.
float analyticFloor(const glm::vec3& origin, const glm::vec3& direction, const Light& l) {
  const glm::dvec3 o(origin), dir(direction);
  const glm::dvec3 p = o + dir * (-o.y / dir.y);
  const glm::dvec3 toLight = glm::dvec3(l.position) - p;
  const double r2 = glm::dot(toLight, toLight);
  const glm::dvec3 wi = toLight / std::sqrt(r2), wo = -dir;
  // Local frame of the floor: x, z tangents, y normal.
  const glm::dvec3 woL(wo.x, wo.z, wo.y), wiL(wi.x, wi.z, wi.y);
  const test::RefMaterial floor{glm::dvec3(0.7), 0.0, 0.6};
  return float(test::refBrdf(floor, woL, wiL).r * wiL.z * l.intensity / r2);
}

// No self-intersection from rebuilt hits: a floor lit at grazing angles by a point light,
// seen through the hybrid, gives the analytic f cos I / r^2 in every pixel, as pt does.
TEST(HybridGrazing, PlaneLitAtGrazingAnglesMatchesTheAnalyticAnswer) {
  Scene s;
  add(s, makeQuad({-20, 0, 20}, {40, 0, 0}, {0, 0, -40}), material(glm::vec3(0.7f), 0, 0.6f));
  Light l;
  l.position = {0, 0.05f, -12};  // 5 cm above the floor: light arrives at 80..89.8 degrees
  l.intensity = 50.0f;
  s.lights.push_back(l);
  addCamera(s, {0, 1.5f, 1}, {0, 0, -4}, 60);
  testing::osmesaContext();
  TraceSettings settings;
  settings.maxBounces = 0;  // direct light only: deterministic for a delta light
  HybridRenderer renderer(s, kWidth, kHeight, settings);
  const EyeCamera cam = monoCamera(s, 0);
  const EyeImage hy = renderer.render({cam, cam}, 1, 0, nullptr)[0];
  const EyeImage pt = renderPathTraced(renderer.traceContext(), cam, 0, 0);
  int checked = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const glm::vec3 dir = cam.pixelRay(x, y);
      if (dir.y >= 0.0f) continue;
      const float expected = analyticFloor(cam.pose.position, dir, l);
      const size_t i = hy.index(x, y);
      // Float rounding of hit points on a 40 m quad (~40 m x 6e-8 = 2.4e-6 m) against light
      // distances >= 4 m and heights >= 5 cm: the grazing cosine (~h / r) moves by up to
      // 2.4e-6 / 0.05 ~ 5e-5 relative; 1e-3 leaves margin and would still catch acne (0).
      // The absolute 1e-6 (image values reach ~1e-2): beyond the light both directions
      // graze and the tracer's flush-to-zero drops denormal BRDF intermediates (~1e-7 here).
      // The reference BRDF is evaluated in double, the renderer's in float: ~1e-6 apart.
      EXPECT_NEAR(hy.color[i].r, expected, 1e-3f * expected + 1e-6f) << x << "," << y;
      EXPECT_NEAR(pt.color[i].r, expected, 1e-3f * expected + 1e-6f) << x << "," << y;
      ++checked;
    }
  EXPECT_GT(checked, kWidth * kHeight / 3);
}

}  // namespace
}  // namespace photovr

namespace photovr {
namespace {

TEST(HybridPipeline, PipelinedReadBackGivesTheSameFramesAsSequential) {
  const Scene scene = mirrorScene();
  testing::osmesaContext();
  HybridRenderer renderer(scene, kWidth, kHeight, TraceSettings{});
  std::vector<std::vector<glm::vec3>> frames[2];
  for (int pipelined = 0; pipelined < 2; ++pipelined)
    renderer.renderSequence(
        [&](uint32_t f) {
          EyeCamera c = monoCamera(scene, f);
          c.pose.position.x += 0.01f * float(f);  // a moving camera: motion vectors change
          return std::array<EyeCamera, 2>{c, c};
        },
        3, 1, pipelined == 1,
        [&](uint32_t, std::array<EyeImage, 2>& images) {
          frames[pipelined].push_back(images[0].color);
        },
        nullptr);
  ASSERT_EQ(frames[0].size(), 3u);
  EXPECT_EQ(frames[0], frames[1]);  // same G-buffers, same seeds: bit-identical
}

TEST(HybridSampleMap, ZeroSamplePixelsAreNotTracedAndCountsFollowTheMap) {
  const Scene scene = mirrorScene();
  testing::osmesaContext();
  HybridRenderer renderer(scene, kWidth, kHeight, TraceSettings{});
  std::vector<uint16_t> map(size_t(kWidth) * kHeight);
  for (size_t i = 0; i < map.size(); ++i) map[i] = uint16_t(i % 3);  // 0, 1, 2, 0, ...
  const EyeCamera cam = monoCamera(scene, 0);
  const EyeImage img = renderer.render({cam, cam}, 1, 0, nullptr, {SampleMap(map), SampleMap()})[0];
  for (size_t i = 0; i < map.size(); ++i) {
    if (img.depth[i] == 0.0f) continue;  // background: the environment, never traced
    EXPECT_EQ(img.samples[i], map[i]) << i;
    if (map[i] == 0) {
      EXPECT_EQ(img.color[i], glm::vec3(0.0f)) << i;
    }
  }
}

}  // namespace
}  // namespace photovr

namespace photovr {
namespace {

// Skipping work must not change what is seen: pixels the DK2 lens never shows are not
// traced (sample map 0), and every other pixel is bit-identical to a uniform render (the
// random numbers are keyed by pixel, not by how many pixels were traced before it).
TEST(SkippedWork, HiddenAreaPixelsChangeNothingElse) {
  const Scene scene = makeBuiltinScene("cornell");
  testing::osmesaContext();
  HybridRenderer renderer(scene, kWidth, kHeight, TraceSettings{});
  std::vector<uint16_t> mask(size_t(kWidth) * kHeight, 1);
  for (size_t i = 0; i < mask.size(); i += 7) mask[i] = 0;  // any pattern of skipped pixels
  StereoRig rig;
  rig.head = poseOf(scene.cameras[0]);
  const EyeCamera cam = rig.eye(Eye::Left, kWidth, kHeight, samplePosition(SamplerKind::Sobol, 0));
  const EyeImage all = renderer.render({cam, cam}, 1, 0, nullptr)[0];
  const EyeImage some =
      renderer.render({cam, cam}, 1, 0, nullptr, {SampleMap(mask), SampleMap()})[0];
  size_t skipped = 0;
  for (size_t i = 0; i < mask.size(); ++i) {
    if (mask[i] == 0) {
      skipped += some.samples[i] == 0;
      continue;
    }
    ASSERT_EQ(all.color[i], some.color[i]) << i;
  }
  EXPECT_EQ(skipped, (mask.size() + 6) / 7);
  EXPECT_LT(some.rays, all.rays);  // the skipped pixels cast no rays
}

}  // namespace
}  // namespace photovr
