// The random (hashed, independent) sampler against the Sobol one (issue 18), same binary,
// same run: trace/rng.h draws every number of a path through one or the other.
//
// 1. Pure path tracing, mono --width x --height (96x96), 8 bounces, one frame of 16, 64
//    and 256 spp, --seeds (8) seeds each: relMSE against a converged reference
//    (harness/reference_cache.*, --reference-spp 4096, its own seed), the mean over the seeds,
//    the Sobol/random ratio, the slope of log relMSE against log spp (least squares over
//    the three counts; -1 is Monte Carlo's rate) and the tracing time per sample. Scenes:
//    every built-in one and the two environment-lit glTF scenes of bench/sampler_scenes.h.
//    The reference's own error adds to every figure; the bench bounds it by the random
//    sampler's 256-spp relMSE x 256 / reference spp (its variance at the reference's count,
//    the reference being at least that good) and prints it, for the trimmed relMSE too (the
//    full one of a firefly-prone scene bounds little). Eight seeds: with three,
//    metal-gltf's 256-spp figures moved by 25 % between runs (its error is mostly sun
//    caustics, rare and large; with 16 seeds 1.15x, with 8 1.22x).
// 2. Hybrid, both eyes at --hybrid-width x --hybrid-height (120x135), 1 spp per frame, 8
//    static frames through the full denoiser (SVGF): relMSE of the 8th frame raw and
//    denoised against a stereo reference (--hybrid-reference-spp 1024), and flicker, the
//    mean |L_t - L_t-1| / mean L_t of consecutive frames 2..8 (camera static, so no
//    re-projection), raw and denoised; mean over the seeds.
// Writes bench_sampler_pt.csv and bench_sampler_hybrid.csv to --out (out/bench).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "gl/render_context.h"
#include "harness/reference_cache.h"
#include "core/view.h"
#include "bench/bench_cli.h"
#include "bench/sampler_scenes.h"
#include "core/error_metrics.h"
#include "core/huge_pages.h"
#include "core/options.h"
#include "core/scene_transform.h"
#include "gl/denoiser.h"
#include "hybrid/denoise_input.h"
#include "hybrid/hybrid_renderer.h"
#include "trace/embree_scene.h"
#include "trace/lights.h"

PHOTOVR_PREINIT(photovr::useHugePagesForMalloc);
namespace photovr {
namespace {

constexpr int kSppCounts[3] = {16, 64, 256};
constexpr SamplerKind kKinds[2] = {SamplerKind::Random, SamplerKind::Sobol};
constexpr int kHybridFrames = 8;

struct Args {
  std::string out = "out/bench";
  int width = 96, height = 96, referenceSpp = 4096, seeds = 8;
  int hybridWidth = 120, hybridHeight = 135, hybridReferenceSpp = 1024;
  std::vector<std::string> scenes = {"atrium", "cornell", "spheres", "metal-gltf", "textured-gltf"};
  bool skipPt = false, skipHybrid = false;
};

struct Setup {
  Scene scene;
  View view;
};

Setup setupScene(const std::string& name, const std::string& dir, bool stereo) {
  Setup s{bench::isGltfScene(name) ? bench::makeGltfScene(name, dir) : makeBuiltinScene(name), {}};
  const Options eyes({"--eyes", stereo ? "stereo" : "mono"}, kViewOptions, {});
  s.view = resolveView(s.scene, eyes);
  if (stereo) s.view.head = recenterOnView(s.scene, s.view.head);
  return s;
}

double secondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Least-squares slope of log y against log x.
double logLogSlope(const std::vector<double>& x, const std::vector<double>& y) {
  double mx = 0, my = 0;
  for (size_t i = 0; i < x.size(); ++i)
    mx += std::log(x[i]) / x.size(), my += std::log(y[i]) / x.size();
  double sxy = 0, sxx = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    const double dx = std::log(x[i]) - mx;
    sxy += dx * (std::log(y[i]) - my);
    sxx += dx * dx;
  }
  return sxy / sxx;
}

// --- 1. Path tracing ---------------------------------------------------------------------

struct PtFigure {
  double relMse = 0.0, trimmed = 0.0, msPerSpp = 0.0;  // means over the seeds
};

PtFigure measurePt(const Setup& s, const EmbreeScene& embree, const LightSet& lights,
                   const std::vector<glm::vec3>& reference, SamplerKind kind, int spp,
                   const Args& a) {
  PtFigure f;
  const EyeCamera cam = eyeCameras(s.view, a.width, a.height, 0, kind)[0];
  for (int seed = 1; seed <= a.seeds; ++seed) {
    TraceSettings settings;
    settings.samplesPerPixel = spp;
    settings.seed = uint32_t(seed);
    settings.sampler = kind;
    const TraceContext ctx{s.scene, embree, lights, settings};
    const auto t0 = std::chrono::steady_clock::now();
    const EyeImage img = renderPathTraced(ctx, cam, 0, 0);
    f.msPerSpp += 1e3 * secondsSince(t0) / spp / a.seeds;
    f.relMse += relMse(img.color, reference) / a.seeds;
    f.trimmed += trimmedRelMse(img.color, reference) / a.seeds;
  }
  return f;
}

void benchPt(const Args& a, std::ofstream& csv) {
  std::printf(
      "\nPure path tracing, mono %dx%d, 8 bounces, relMSE (mean of %d seeds) against a"
      " %d-spp reference:\n",
      a.width, a.height, a.seeds, a.referenceSpp);
  std::printf("  %-14s %5s %9s %9s %6s | %9s %9s %6s | %8s %8s\n", "scene", "spp", "random",
              "sobol", "ratio", "trim rnd", "trim sob", "ratio", "rnd ms/s", "sob ms/s");
  csv << "scene,width,height,spp,sampler,seeds,relmse,trimmed_relmse,ms_per_spp,reference_spp\n";
  for (const std::string& name : a.scenes) {
    const Setup s = setupScene(name, a.out, false);
    const harness::Reference ref =
        harness::loadOrRenderReference({&s.scene, s.view, a.width, a.height, 8}, a.referenceSpp);
    const EmbreeScene embree(s.scene);
    const LightSet lights(s.scene);
    std::vector<double> spps, errors[2], trimmed[2];
    for (int spp : kSppCounts) {
      PtFigure f[2];
      for (int k = 0; k < 2; ++k) {
        f[k] = measurePt(s, embree, lights, ref.eyes[0], kKinds[k], spp, a);
        errors[k].push_back(f[k].relMse);
        trimmed[k].push_back(f[k].trimmed);
        csv << name << ',' << a.width << ',' << a.height << ',' << spp << ','
            << samplerName(kKinds[k]) << ',' << a.seeds << ',' << f[k].relMse << ',' << f[k].trimmed
            << ',' << f[k].msPerSpp << ',' << ref.samplesPerPixel << '\n';
      }
      spps.push_back(spp);
      std::printf("  %-14s %5d %9.5f %9.5f %5.2fx | %9.5f %9.5f %5.2fx | %8.1f %8.1f\n",
                  name.c_str(), spp, f[0].relMse, f[1].relMse, f[0].relMse / f[1].relMse,
                  f[0].trimmed, f[1].trimmed, f[0].trimmed / f[1].trimmed, f[0].msPerSpp,
                  f[1].msPerSpp);
    }
    const double refShare = 256.0 / ref.samplesPerPixel;
    std::printf(
        "  %-14s slope of log relMSE / log spp: random %.2f, sobol %.2f (trimmed %.2f,"
        " %.2f); reference error <= %.1e (trimmed %.1e)\n",
        name.c_str(), logLogSlope(spps, errors[0]), logLogSlope(spps, errors[1]),
        logLogSlope(spps, trimmed[0]), logLogSlope(spps, trimmed[1]), errors[0].back() * refShare,
        trimmed[0].back() * refShare);
  }
}

// --- 2. Hybrid, 1 spp, denoised ----------------------------------------------------------

double luminance(const glm::vec3& c) {
  return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
}

// Mean |L_now - L_before| / mean L_now over both eyes' pixels.
double frameChange(const std::array<std::vector<glm::vec3>, 2>& now,
                   const std::array<std::vector<glm::vec3>, 2>& before) {
  double diff = 0.0, sum = 0.0;
  for (int e = 0; e < 2; ++e)
    for (size_t i = 0; i < now[e].size(); ++i) {
      diff += std::abs(luminance(now[e][i]) - luminance(before[e][i]));
      sum += luminance(now[e][i]);
    }
  return sum > 0.0 ? diff / sum : 0.0;
}

double relMseBothEyes(const std::array<std::vector<glm::vec3>, 2>& img,
                      const harness::Reference& ref) {
  return 0.5 * (relMse(img[0], ref.eyes[0]) + relMse(img[1], ref.eyes[1]));
}

struct HybridFigure {
  double raw = 0.0, denoised = 0.0, rawFlicker = 0.0, denoisedFlicker = 0.0;
};

// One seed's 8 frames; adds its figures / 'share' to 'f'.
void runHybrid(const Setup& s, const harness::Reference& ref, SamplerKind kind, uint32_t seed,
               const Args& a, double share, HybridFigure& f) {
  const int w = a.hybridWidth, h = a.hybridHeight;
  TraceSettings settings;
  settings.seed = seed;
  settings.sampler = kind;
  HybridRenderer r(s.scene, w, h, settings);
  gl::Denoiser dn(w, h);
  std::array<std::vector<glm::vec3>, 2> raw, denoised, lastRaw, lastDenoised;
  for (int frame = 0; frame < kHybridFrames; ++frame) {
    const std::array<EyeImage, 2> images =
        r.render(eyeCameras(s.view, w, h, uint32_t(frame), kind), 2, uint32_t(frame), nullptr);
    const DenoiseInput in[2] = {makeDenoiseInput(images[0]), makeDenoiseInput(images[1])};
    dn.run(r.gbuffer(), {in[0].eye, in[1].eye}, 2, gl::DenoiseMode::Full, frame == 0);
    for (int e = 0; e < 2; ++e) raw[e] = images[e].color, denoised[e] = dn.readLinear(e);
    if (frame > 0) {
      const double frames = kHybridFrames - 1;
      f.rawFlicker += frameChange(raw, lastRaw) / frames * share;
      f.denoisedFlicker += frameChange(denoised, lastDenoised) / frames * share;
    }
    lastRaw = raw;
    lastDenoised = denoised;
  }
  f.raw += relMseBothEyes(raw, ref) * share;
  f.denoised += relMseBothEyes(denoised, ref) * share;
}

void benchHybrid(const Args& a, std::ofstream& csv) {
  const std::unique_ptr<gl::Context> ctx = gl::createRenderContext("");
  std::printf(
      "\nHybrid, both eyes %dx%d, 1 spp x %d static frames, full denoiser; relMSE of"
      " the last frame and flicker (mean of %d seeds) against a %d-spp reference:\n",
      a.hybridWidth, a.hybridHeight, kHybridFrames, a.seeds, a.hybridReferenceSpp);
  std::printf("  %-14s %-7s %9s %9s | %9s %9s\n", "scene", "sampler", "raw", "denoised", "flk raw",
              "flk den");
  csv << "scene,eye_width,eye_height,frames,sampler,seeds,raw_relmse,denoised_relmse,"
         "raw_flicker,denoised_flicker,reference_spp\n";
  for (const std::string& name : a.scenes) {
    const Setup s = setupScene(name, a.out, true);
    const harness::Reference ref = harness::loadOrRenderReference(
        {&s.scene, s.view, a.hybridWidth, a.hybridHeight, 8}, a.hybridReferenceSpp);
    for (SamplerKind kind : kKinds) {
      HybridFigure f;
      for (int seed = 1; seed <= a.seeds; ++seed)
        runHybrid(s, ref, kind, uint32_t(seed), a, 1.0 / a.seeds, f);
      std::printf("  %-14s %-7s %9.4f %9.4f | %9.4f %9.4f\n", name.c_str(), samplerName(kind),
                  f.raw, f.denoised, f.rawFlicker, f.denoisedFlicker);
      csv << name << ',' << a.hybridWidth << ',' << a.hybridHeight << ',' << kHybridFrames << ','
          << samplerName(kind) << ',' << a.seeds << ',' << f.raw << ',' << f.denoised << ','
          << f.rawFlicker << ',' << f.denoisedFlicker << ',' << ref.samplesPerPixel << '\n';
    }
  }
}

const char* const kUsage =
    "usage: photovr_bench_sampler [--out DIR] [--width W] [--height H] [--reference-spp N]\n"
    "                             [--seeds N] [--hybrid-width W] [--hybrid-height H]\n"
    "                             [--hybrid-reference-spp N] [--scenes NAME]\n"
    "                             [--skip-pt] [--skip-hybrid]\n"
    "The random sampler against the Sobol one: pure path-traced relMSE at 16, 64 and 256 spp\n"
    "(mono W x H, 96x96) against a cached --reference-spp (4096) reference, with the slope of\n"
    "log relMSE against log spp and the time per sample; and 1-spp hybrid frames through the\n"
    "full denoiser (both eyes, 120x135, 8 frames): relMSE and flicker. Every built-in scene\n"
    "and the glTF scenes metal-gltf and textured-gltf (written to --out), or --scenes NAME;\n"
    "--seeds (8) seeds each. Writes bench_sampler_pt.csv and bench_sampler_hybrid.csv to\n"
    "--out (out/bench).\n";

Args parse(const Options& o) {
  Args a;
  a.out = o.text("--out", a.out);
  a.width = o.integer("--width", a.width, 8, 4096);
  a.height = o.integer("--height", a.height, 8, 4096);
  a.referenceSpp = o.integer("--reference-spp", a.referenceSpp, 256, 1 << 20);
  a.seeds = o.integer("--seeds", a.seeds, 1, 64);
  a.hybridWidth = o.integer("--hybrid-width", a.hybridWidth, 8, 4096);
  a.hybridHeight = o.integer("--hybrid-height", a.hybridHeight, 8, 4096);
  a.hybridReferenceSpp = o.integer("--hybrid-reference-spp", a.hybridReferenceSpp, 16, 1 << 20);
  if (o.has("--scenes")) {
    const std::string name = o.text("--scenes", "");
    if (!bench::isGltfScene(name) && !isBuiltinScene(name))
      throw UsageError("--scenes: unknown scene '" + name +
                       "' (valid: atrium, cornell, spheres, metal-gltf, textured-gltf)");
    a.scenes = {name};
  }
  a.skipPt = o.has("--skip-pt");
  a.skipHybrid = o.has("--skip-hybrid");
  return a;
}

int run(const Options& options) {
  const Args a = parse(options);
  std::filesystem::create_directories(a.out);
  if (!a.skipPt) {
    std::ofstream csv(a.out + "/bench_sampler_pt.csv");
    benchPt(a, csv);
  }
  if (!a.skipHybrid) {
    std::ofstream csv(a.out + "/bench_sampler_hybrid.csv");
    benchHybrid(a, csv);
  }
  std::printf("wrote %s/bench_sampler_*.csv\n", a.out.c_str());
  return 0;
}

}  // namespace
}  // namespace photovr

int main(int argc, char** argv) {
  return photovr::benchMain(
      argc, argv, photovr::kUsage,
      {"--out", "--width", "--height", "--reference-spp", "--seeds", "--hybrid-width",
       "--hybrid-height", "--hybrid-reference-spp", "--scenes"},
      {"--skip-pt", "--skip-hybrid"}, photovr::run);
}
