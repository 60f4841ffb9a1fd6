// Caustics of directional lights by light tracing (trace/caustics.h): the light tracer's
// value against a closed form, and the two tracers' partition of the paths against the path
// tracer alone.
#include "trace/caustics.h"

#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "core/builtin_scenes.h"
#include "core/mesh_gen.h"
#include "tests/trace/image_statistics.h"
#include "tests/trace/trace_test_util.h"
#include "trace/path_tracer.h"

namespace photovr {
namespace {

constexpr int kW = 32, kH = 32;

struct Fixture {
  Scene scene;
  EmbreeScene embree;
  LightSet lights;
  TraceContext ctx;
  explicit Fixture(Scene s, bool caustics)
      : scene(std::move(s)), embree(scene), lights(scene), ctx{scene, embree, lights, {}} {
    ctx.settings.caustics = caustics;
  }
};

Light sunAlong(const glm::vec3& travels, float lux) {
  Light l;
  l.type = Light::Type::Directional;
  l.direction = glm::normalize(travels);
  l.intensity = lux;
  return l;
}

EyeCamera cameraAt(const glm::vec3& from, const glm::vec3& at, uint32_t frame, float yfov = 0.5f,
                   int size = kW) {
  EyeCamera c;
  c.pose = lookAt(from, at);
  c.fov = FovTangents::symmetric(yfov, 1.0f);
  c.width = c.height = size;
  c.jitter = samplePosition(SamplerKind::Sobol, frame);
  return c;
}

BsdfParams constantBsdf(const Material& m) {
  BsdfParams b;
  b.baseColor = glm::vec3(m.baseColorFactor);
  b.metallic = m.metallicFactor;
  b.roughness = m.roughnessFactor;
  return b;
}

// Calls visit(pixel, direction, point) for each pixel of 'cam' whose centre ray meets
// 'instance', at that point.
template <typename Visit>
void forPixelsSeeing(const Fixture& f, const EyeCamera& cam, uint32_t instance, Visit&& visit) {
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      const glm::vec3 dir = cam.rayDirection(x + 0.5f, y + 0.5f);
      const TraceHit h = f.embree.intersect(cam.pose.position, dir, 0.0f, 1e30f);
      if (h.hit && h.instance == instance)
        visit(size_t(y) * size_t(cam.width) + size_t(x), dir, cam.pose.position + h.t * dir);
    }
}

// The mean over frames of a frame's mean of read / expected over the pixels 'expected' names
// (pixel, expected luminance), and that mean's standard error. readFrame(k): frame k's
// luminance per pixel.
struct ReadOverExpected {
  double mean = 0.0, error = 0.0;
};
ReadOverExpected readOverExpected(const std::vector<std::pair<size_t, double>>& expected,
                                  int frames,
                                  const std::function<std::vector<double>(uint32_t)>& readFrame) {
  std::vector<double> perFrame;
  for (int k = 0; k < frames; ++k) {
    const std::vector<double> read = readFrame(uint32_t(k));
    double sum = 0.0;
    for (const auto& [i, want] : expected) sum += read[i] / want;
    perFrame.push_back(sum / double(expected.size()));
  }
  ReadOverExpected r;
  for (const double v : perFrame) r.mean += v / frames;
  double var = 0.0;
  for (const double v : perFrame) var += (v - r.mean) * (v - r.mean) / (frames - 1);
  r.error = std::sqrt(var / frames);
  return r;
}

// A 1 m mirror (metal, white, roughness 0) at height 1 facing +x and down at 45 degrees, a
// white-ish rough floor, and a sun along -x: the mirror throws the sun straight down, onto
// the floor beneath it, which nothing else lights (the sun grazes it).
Scene mirrorOverFloor() {
  Scene s;
  Material mirror;
  mirror.baseColorFactor = glm::vec4(1.0f);
  mirror.metallicFactor = 1.0f;
  mirror.roughnessFactor = 0.0f;
  s.materials = {testing::diffuseMaterial(glm::vec3(0.5f)), mirror};
  // squareMesh faces +z; turned to face (1, -1, 0) / sqrt 2.
  const glm::mat4 tilt = glm::rotate(glm::translate(glm::mat4(1.0f), {0.0f, 1.0f, 0.0f}),
                                     glm::radians(90.0f), glm::vec3(0, 1, 0)) *
                         glm::rotate(glm::mat4(1.0f), glm::radians(45.0f), glm::vec3(1, 0, 0));
  testing::addSquare(s, 0.5f, 1, tilt);
  testing::addSquare(s, 3.0f, 0,
                     glm::rotate(glm::mat4(1.0f), glm::radians(-90.0f), glm::vec3(1, 0, 0)));
  s.lights.push_back(sunAlong({-1, 0, 0}, 3.0f));
  return s;
}

// The mirror's lobe reflects the sun to (0, -1, 0): the floor beneath it is lit with the
// sun's irradiance E times the mirror's directional albedo, 1 for F0 = 1 up to GGX's
// masking at 45 degrees (Lambda ~ alpha^2 / 4 = 1e-6) and the part of its tail (0.2 %
// beyond 5 degrees, bsdf.h) that leaves the lit patch. Only the light tracer sees it: the
// path tracer's bounce from the floor lands in a lobe ~alpha wide around the sun's mirror
// image with probability ~1e-6. So each pixel that sees the patch's interior must read
// f_floor(wo, up) E, within Monte Carlo error over frames plus 1 % for the tail.
// Viewed from 'eye' towards 'target' with a yfov x yfov field at size x size pixels.
void expectTheMirrorsPatch(const glm::vec3& eye, const glm::vec3& target, float yfov, int size) {
  Fixture f(mirrorOverFloor(), true);
  // The pixels whose centre sees the floor inside the patch, 0.1 m from its edges (the
  // mirror spans x in +-0.354, z in +-0.5), and what each must read.
  const BsdfParams floor = constantBsdf(f.scene.materials[0]);
  std::vector<std::pair<size_t, double>> inside;  // pixel, expected luminance
  float leastCosine = 1.0f;                       // of a pixel's ray to the view axis
  forPixelsSeeing(f, cameraAt(eye, target, 0, yfov, size), 1,
                  [&](size_t pixel, const glm::vec3& dir, const glm::vec3& p) {
                    if (std::abs(p.x) > 0.25f || p.z < 0.0f || p.z > 0.4f) return;
                    // In a frame of the floor, z up (world y): wo towards the eye, wi straight
                    // up (the BRDF is isotropic: any tangents do).
                    const glm::vec3 woLocal(-dir.x, dir.z, -dir.y);
                    const glm::vec3 fv = evalBsdf(floor, woLocal, glm::vec3(0, 0, 1)) * 3.0f;
                    inside.emplace_back(pixel, luminance(fv));
                    leastCosine =
                        std::min(leastCosine, glm::dot(dir, glm::normalize(target - eye)));
                  });
  ASSERT_GT(inside.size(), 20u);
  const ReadOverExpected r = readOverExpected(inside, 256, [&](uint32_t k) {
    const EyeImage img = renderPathTraced(f.ctx, cameraAt(eye, target, k, yfov, size), 0, k);
    std::vector<double> read;
    for (const glm::vec3& c : img.color) read.push_back(luminance(c));
    return read;
  });
  std::printf("  %zu pixels, cos to the view axis down to %.2f: read / expected %.4f +- %.4f\n",
              inside.size(), leastCosine, r.mean, r.error);
  EXPECT_NEAR(r.mean, 1.0, 4.0 * r.error + 0.01);
}

// The mirror's lobe reflects the sun to (0, -1, 0): the floor beneath it is lit with the
// sun's irradiance E times the mirror's directional albedo, 1 for F0 = 1 up to GGX's
// masking at 45 degrees (Lambda ~ alpha^2 / 4 = 1e-6) and the part of its tail (0.2 %
// beyond 5 degrees, bsdf.h) that leaves the lit patch. Only the light tracer sees it: the
// path tracer's bounce from the floor lands in a lobe ~alpha wide around the sun's mirror
// image with probability ~1e-6. So each pixel that sees the patch's interior must read
// f_floor(wo, up) E, within Monte Carlo error over frames plus 1 % for the tail: seen near
// the view axis, and near the corner of a wide field (where the pinhole's importance,
// 1 / cos^3, is 2-3 times the axis's).
TEST(Caustics, AMirrorThrowsTheSunOntoTheFloorWithItsIrradiance) {
  expectTheMirrorsPatch({0.6f, 2.0f, 2.0f}, {-0.1f, 0.0f, 0.3f}, 0.5f, kW);
  expectTheMirrorsPatch({0.6f, 2.0f, 2.0f}, {-1.4f, 0.9f, -0.4f}, 1.8f, 96);
}

// The mirror over the floor and a white wall (0.6 m square, instance 2) at x = 1.2 facing
// the mirror, below the sun's beam: the patch the mirror lights on the floor lights the wall.
Scene mirrorFloorAndWall() {
  Scene s = mirrorOverFloor();
  s.materials.push_back(testing::diffuseMaterial(glm::vec3(0.8f)));
  testing::addSquare(s, 0.3f, 2,
                     glm::rotate(glm::translate(glm::mat4(1.0f), {1.2f, 0.3f, 0.0f}),
                                 glm::radians(-90.0f), glm::vec3(0, 1, 0)));
  return s;
}

// The wall's radiance towards 'eye' at its point p lit by the mirror's patch on the floor
// (x in +-0.3536, z in +-0.5, irradiance E = 3 straight down: the closed form above), by
// an n x n midpoint quadrature over the patch.
double wallByQuadrature(const Fixture& f, const glm::vec3& eye, const glm::vec3& p, int n) {
  const BsdfParams floor = constantBsdf(f.scene.materials[0]),
                   wall = constantBsdf(f.scene.materials[2]);
  const Frame wallFrame = Frame::fromZ({-1.0f, 0.0f, 0.0f}), floorFrame = Frame::fromZ({0, 1, 0});
  const glm::vec3 woWall = wallFrame.toLocal(glm::normalize(eye - p));
  const float halfX = 0.5f * std::sqrt(0.5f);  // the mirror's half width seen from above
  double sum = 0.0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const glm::vec3 q(halfX * (2.0f * (i + 0.5f) / n - 1.0f), 0.0f, (j + 0.5f) / n - 0.5f);
      glm::vec3 d = p - q;
      const float r = glm::length(d);
      d /= r;
      if (f.embree.occluded(q + glm::vec3(0, 1e-4f, 0), d, 0.0f, r - 2e-3f)) continue;
      const glm::vec3 leavesFloor = floorFrame.toLocal(d), reachesWall = wallFrame.toLocal(-d);
      const glm::vec3 c = evalBsdf(wall, woWall, reachesWall) *
                          evalBsdf(floor, leavesFloor, glm::vec3(0, 0, 1)) *
                          (3.0f * leavesFloor.z * reachesWall.z / (r * r));
      sum += luminance(c);
    }
  return sum * (2.0 * halfX) * 1.0 / (double(n) * n);
}

// A light path goes on from the receiver it lit to the next (kCausticReceivers): the sun,
// the mirror, the floor beneath it, the wall. Only the light tracer has that light (the path
// tracer's third vertex would have to meet the mirror's peak). Its splats on the wall's
// interior pixels must give the quadrature's radiance, region-wide within their Monte Carlo
// error over frames plus 1.5 % (the mirror's tail, 0.2 % beyond 5 degrees, and each pixel
// read at its centre).
TEST(Caustics, TheReceiverALightPathLitLightsTheNext) {
  Fixture f(mirrorFloorAndWall(), true);
  const glm::vec3 eye(-0.6f, 0.45f, 1.6f), target(1.2f, 0.3f, 0.0f);
  constexpr float kYfov = 0.2f;
  std::vector<std::pair<size_t, double>> inside;  // pixel, expected luminance
  forPixelsSeeing(f, cameraAt(eye, target, 0, kYfov), 2,
                  [&](size_t pixel, const glm::vec3&, const glm::vec3& p) {
                    if (p.y < 0.05f || p.y > 0.55f || std::abs(p.z) > 0.25f) return;
                    inside.emplace_back(pixel, wallByQuadrature(f, eye, p, 48));
                  });
  ASSERT_GT(inside.size(), 40u);
  const CausticSources sources(f.scene, f.embree.bounds());
  constexpr uint32_t kPaths = 1u << 16;
  const ReadOverExpected r = readOverExpected(inside, 96, [&](uint32_t k) {
    std::vector<double> read(kW * kH, 0.0);
    for (const CausticSplat& s :
         traceCaustics(f.ctx, sources, cameraAt(eye, target, k, kYfov), k, kPaths))
      if (s.pixel != ~0u) read[s.pixel] += luminance(s.diffuse + s.specular) / kPaths;
    return read;
  });
  std::printf("  %zu pixels of the wall: read / expected %.4f +- %.4f\n", inside.size(), r.mean,
              r.error);
  EXPECT_NEAR(r.mean, 1.0, 4.0 * r.error + 0.015);
}

// A glossy metal square (roughness 0.25, a caster) turned as the mirror above, over the
// same floor, lit by a sun travelling along 'sunTravels'; nothing else.
Scene glossySquareOverFloor(const glm::vec3& sunTravels) {
  Scene s = mirrorOverFloor();
  s.materials[1].baseColorFactor = glm::vec4(0.9f, 0.6f, 0.3f, 1.0f);
  s.materials[1].roughnessFactor = 0.25f;
  s.lights = {sunAlong(sunTravels, 3.0f)};
  return s;
}

const glm::vec3 kSideEye(1.5f, 1.6f, 2.5f), kSideTarget(-0.4f, 0.3f, 0.0f);

// The caustic's radiance towards the eye through pixel (x, y) of 'cam': the partition's
// integral (caustics.h) by quadrature, x1 at n x n points of the pixel, x2 at g x g points
// of the square (instance 0, side 1), the floor (instance 1) as the only receiver.
double causticByQuadrature(const Fixture& f, const EyeCamera& cam, int x, int y, int n, int g) {
  const glm::vec3 toSun = -glm::normalize(f.scene.lights[0].direction);
  const glm::mat4& square = f.scene.instances[0].transform;
  glm::vec3 n2 = glm::normalize(glm::vec3(square * glm::vec4(0, 0, 1, 0)));
  if (glm::dot(n2, toSun) < 0.0f) n2 = -n2;  // the lit side
  const Frame frame2 = Frame::fromZ(n2);
  const glm::vec3 sun2 = frame2.toLocal(toSun);
  const BsdfParams& metal = f.embree.materials().constantOf(1)->bsdf;
  double sum = 0.0;
  for (int sy = 0; sy < n; ++sy)
    for (int sx = 0; sx < n; ++sx) {
      const glm::vec3 dir = cam.rayDirection(x + (sx + 0.5f) / n, y + (sy + 0.5f) / n);
      const TraceHit h = f.embree.intersect(cam.pose.position, dir, 0.0f, 1e30f);
      if (!h.hit || h.instance != 1) continue;
      const SurfaceHit x1 = surfaceAt(f.scene, h.instance, h.triangle, h.b1, h.b2, dir);
      const Frame frame1 = Frame::fromZ(x1.shadingNormal);
      for (int i = 0; i < g; ++i)
        for (int j = 0; j < g; ++j) {
          const glm::vec3 x2(square *
                             glm::vec4(-0.5f + (i + 0.5f) / g, -0.5f + (j + 0.5f) / g, 0.0f, 1.0f));
          glm::vec3 d = x1.position - x2;
          const float r = glm::length(d);
          d /= r;
          if (glm::dot(n2, d) <= 0.0f || glm::dot(x1.geometricNormal, d) >= 0.0f) continue;
          if (f.embree.occluded(x2 + 1e-4f * n2, d, 0.0f, r - 2e-3f)) continue;
          const glm::vec3 wi1 = frame1.toLocal(-d);
          const glm::vec3 c = evalBsdf(x1.bsdf, frame1.toLocal(-dir), wi1) *
                              evalBsdfLobes(metal, frame2.toLocal(d), sun2).specular *
                              (3.0f * sun2.z * glm::dot(n2, d) * wi1.z / (r * r));
          sum += luminance(c);
        }
    }
  return sum / (double(n) * n * double(g) * g);  // the square's area is 1
}

// Under a low sun (cos 0.1 on the square) the path tracer meets the caustic only in the rare
// bounces that land in the lobe's peak; the light tracer alone must give it, region by region
// (4 x 4 pixels), within its own Monte Carlo error (over frames) plus 3 % for the quadrature's
// grids (2 x 2 points a pixel, 1 cm on the square; the lobe is ~7 degrees wide).
TEST(Caustics, TheLightTracerGivesTheCausticOfAGlossySquareUnderALowSun) {
  Fixture f(glossySquareOverFloor({-1.0f, -0.8f, -0.4f}), true);
  f.ctx.settings.maxBounces = 1;  // x1 only: what the quadrature integrates
  const CausticSources sources(f.scene, f.embree.bounds());
  constexpr int kSize = 16, kCell = 4, kFrames = 512;
  std::vector<double> sum(kSize * kSize, 0.0), sumSq(kSize * kSize, 0.0);
  for (int k = 0; k < kFrames; ++k) {
    EyeCamera cam = cameraAt(kSideEye, kSideTarget, uint32_t(k));
    cam.width = cam.height = kSize;
    const uint32_t paths = causticPathCount(kSize, kSize) * 8;
    std::vector<double> frame(kSize * kSize, 0.0);
    for (const CausticSplat& s : traceCaustics(f.ctx, sources, cam, uint32_t(k), paths))
      if (s.pixel != ~0u)
        frame[s.pixel / kSize / kCell * (kSize / kCell) + s.pixel % kSize / kCell] +=
            luminance(s.diffuse + s.specular) / paths;
    for (int i = 0; i < kSize * kSize; ++i) sum[i] += frame[i], sumSq[i] += frame[i] * frame[i];
  }
  EyeCamera cam = cameraAt(kSideEye, kSideTarget, 0);
  cam.width = cam.height = kSize;
  int lit = 0;
  for (int ry = 0; ry < kSize / kCell; ++ry)
    for (int rx = 0; rx < kSize / kCell; ++rx) {
      double want = 0.0;
      for (int y = ry * kCell; y < (ry + 1) * kCell; ++y)
        for (int x = rx * kCell; x < (rx + 1) * kCell; ++x)
          want += causticByQuadrature(f, cam, x, y, 2, 100);
      const int r = ry * (kSize / kCell) + rx;
      const double mean = sum[r] / kFrames;
      const double error = std::sqrt(std::max(0.0, sumSq[r] / kFrames - mean * mean) / kFrames);
      lit += want > 0.01;
      std::printf("  region (%d, %d): light tracer %.4f +- %.4f, quadrature %.4f\n", rx, ry, mean,
                  error, want);
      EXPECT_NEAR(mean, want, 4.0 * error + 0.03 * want + 1e-4) << rx << ", " << ry;
    }
  EXPECT_GE(lit, 3) << "the caustic must reach several regions for the test to mean much";
}

// The partition holds only for paths whose vertices before the caster are all receivers: a
// path that meets a non-receiver first (the square at roughness 0.1, a caster but no
// receiver) keeps its next-event estimation at every later caster, and the light tracer
// never lands on the pixels that see it. So those pixels read the same with caustics on as
// off, to the bit (the path tracer draws the same numbers either way), while the image
// elsewhere changes. Paths square - floor - square - sun are there: GGX's tails make every
// such NEE sample count.
TEST(Caustics, PathsThatMeetANonReceiverFirstKeepTheirCaustics) {
  const glm::vec3 highSun(-1.0f, -0.1f, -0.2f);
  Scene scene = glossySquareOverFloor(highSun);
  scene.materials[1].roughnessFactor = 0.1f;
  Fixture on(scene, true), off(scene, false);
  ASSERT_TRUE(causticCaster(on.embree.materials().constantOf(1)->bsdf));
  ASSERT_FALSE(causticReceiver(on.embree.materials().constantOf(1)->bsdf));
  const EyeCamera cam = cameraAt(kSideEye, kSideTarget, 0);
  std::vector<size_t> square;  // pixels whose every corner sees the square
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      bool all = true;
      for (const glm::vec2 c :
           {glm::vec2(0, 0), glm::vec2(1, 0), glm::vec2(0, 1), glm::vec2(1, 1)}) {
        const TraceHit h =
            on.embree.intersect(kSideEye, cam.rayDirection(x + c.x, y + c.y), 0.0f, 1e30f);
        all = all && h.hit && h.instance == 0;
      }
      if (all) square.push_back(size_t(y) * kW + size_t(x));
    }
  ASSERT_GT(square.size(), 30u);
  size_t elsewhere = 0;
  for (int k = 0; k < 4; ++k) {
    const EyeCamera c = cameraAt(kSideEye, kSideTarget, uint32_t(k));
    const EyeImage a = renderPathTraced(on.ctx, c, 0, uint32_t(k)),
                   b = renderPathTraced(off.ctx, c, 0, uint32_t(k));
    for (const size_t i : square)
      ASSERT_EQ(a.color[i], b.color[i]) << "pixel " << i << ", frame " << k;
    for (size_t i = 0; i < a.color.size(); ++i) elsewhere += a.color[i] != b.color[i];
  }
  EXPECT_GT(elsewhere, 100u) << "caustics changed nothing anywhere";
}

std::vector<std::vector<glm::vec3>> framesOf(const TraceContext& ctx, int frames) {
  std::vector<std::vector<glm::vec3>> out;
  for (int k = 0; k < frames; ++k)
    out.push_back(
        renderPathTraced(ctx, cameraAt(kSideEye, kSideTarget, uint32_t(k)), 0, uint32_t(k)).color);
  return out;
}

// Under a high sun the path tracer alone finds the glossy square's caustic well, and must
// agree with the two tracers together: every path the light tracer takes, next-event
// estimation leaves out, and no other. Region z-tests (tests/trace/image_statistics.h),
// unpaired and on paired frames (the path tracer draws the same numbers with caustics on).
// Under a low sun this comparison cannot work: the path tracer's few peak samples are all
// its estimate has, and a z-test on its sample variance over 128-1024 frames reads the
// light tracer's steady value against them as a 6-13 sigma difference (docs/MEASUREMENTS.md),
// hence the quadrature above. 8192 frames: the second receiver's paths (square - floor -
// square - sun) are heavy-tailed in the path tracer alone even under a high sun; paired
// |z| read 4.3, 7.1, 2.0 and 3.8 at 256-2048 frames, then 1.7, 1.3 and 1.6 at 4096-16384,
// with no trend with the frames (no bias), against 48.8 with the exclusion at the second
// receiver dropped.
TEST(Caustics, TheLightTracerAndThePathTracerSplitThePathsWithoutBias) {
  const glm::vec3 highSun(-1.0f, -0.1f, -0.2f);
  Fixture on(glossySquareOverFloor(highSun), true), off(glossySquareOverFloor(highSun), false);
  constexpr int kFrames = 8192;
  const auto a = framesOf(on.ctx, kFrames), b = framesOf(off.ctx, kFrames);
  double added = 0.0;  // what the light tracer added over the frames: the test must see it
  const CausticSources sources(on.scene, on.embree.bounds());
  for (int k = 0; k < 16; ++k)
    for (const CausticSplat& s : traceCaustics(on.ctx, sources, cameraAt(kSideEye, kSideTarget, 0),
                                               uint32_t(k), causticPathCount(kW, kH)))
      added += luminance(s.diffuse + s.specular) / causticPathCount(kW, kH) / 16;
  const double z = testing::maxRegionZ(testing::statisticsOf(a, kW, kH),
                                       testing::statisticsOf(b, kW, kH), testing::kRegions);
  const double paired = testing::maxPairedRegionZ(a, b, kW, kH, testing::kRegions);
  std::printf("  light tracer's share of the image %.1f; max region |z| %.2f, paired %.2f\n", added,
              z, paired);
  EXPECT_GT(added, 1.0);
  EXPECT_LT(z, testing::kMaxZ);
  EXPECT_LT(paired, testing::kMaxZ);
}

// The light paths' numbers depend on the seed, frame and path alone, and each path writes
// its own slot: a frame is the same bits at any thread count.
TEST(Caustics, FramesAreBitIdenticalWhateverTheThreadCount) {
  Fixture f(makeBuiltinScene("spheres"), true);
  StereoRig rig;
  rig.head = poseOf(f.scene.cameras.at(0));
  const EyeCamera cam = rig.eye(Eye::Left, 40, 45, samplePosition(SamplerKind::Sobol, 3));
  std::vector<glm::vec3> one, two;
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
    one = renderPathTraced(f.ctx, cam, 0, 3).color;
  }
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
    two = renderPathTraced(f.ctx, cam, 0, 3).color;
  }
  ASSERT_EQ(one.size(), two.size());
  EXPECT_EQ(0, std::memcmp(one.data(), two.data(), one.size() * sizeof(glm::vec3)));
  Fixture without(makeBuiltinScene("spheres"), false);
  EXPECT_NE(one, renderPathTraced(without.ctx, cam, 0, 3).color) << "caustics changed nothing";
}

// A light-traced caustic is indirect light (the sun reaches x1 through x2), which
// --bounces 0 leaves out: there the path tracer has no second vertex whose next-event
// estimation leaves anything to the light tracer, so caustics on are caustics off, to the bit.
TEST(Caustics, NoBouncesNoCaustics) {
  Fixture on(makeBuiltinScene("spheres"), true), off(makeBuiltinScene("spheres"), false);
  on.ctx.settings.maxBounces = off.ctx.settings.maxBounces = 0;
  StereoRig rig;
  rig.head = poseOf(on.scene.cameras.at(0));
  const EyeCamera cam = rig.eye(Eye::Left, 40, 45, samplePosition(SamplerKind::Sobol, 2));
  const EyeImage a = renderPathTraced(on.ctx, cam, 0, 2), b = renderPathTraced(off.ctx, cam, 0, 2);
  ASSERT_EQ(a.color.size(), b.color.size());
  EXPECT_EQ(0, std::memcmp(a.color.data(), b.color.data(), a.color.size() * sizeof(glm::vec3)));
  EXPECT_EQ(a.rays, b.rays) << "light paths were traced";
}

// The eyes of a stereo frame share its light paths (CausticPaths): the second eye connects
// the first's paths to itself, and its image is the one it gets tracing them itself, to the
// bit (the paths' numbers do not depend on the eye).
TEST(Caustics, TheEyesOfAFrameShareItsLightPaths) {
  Fixture f(makeBuiltinScene("spheres"), true);
  StereoRig rig;
  rig.head = poseOf(f.scene.cameras.at(0));
  const glm::vec2 jitter = samplePosition(SamplerKind::Sobol, 5);
  const EyeCamera left = rig.eye(Eye::Left, 40, 45, jitter),
                  right = rig.eye(Eye::Right, 40, 45, jitter);
  CausticPaths shared;
  StereoRole role;
  role.caustics = &shared;
  const EyeImage l = renderPathTraced(f.ctx, left, 0, 5, {}, role);
  ASSERT_TRUE(shared.holds(f.ctx, 5, causticPathCount(40, 45)));
  const uint64_t leftRays = l.rays;
  const EyeImage r = renderPathTraced(f.ctx, right, 1, 5, {}, role);
  const EyeImage own = renderPathTraced(f.ctx, right, 1, 5);
  ASSERT_EQ(r.color.size(), own.color.size());
  EXPECT_EQ(0, std::memcmp(r.color.data(), own.color.data(), r.color.size() * sizeof(glm::vec3)));
  EXPECT_LT(r.rays, own.rays) << "the second eye traced the light paths again";
  EXPECT_GT(leftRays, 0u);
}

}  // namespace
}  // namespace photovr
