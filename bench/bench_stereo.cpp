// Stereo path reuse (issue 21, trace/stereo_reuse.h): what the right eye costs and what the
// frame's time buys, reuse on against off, same run, every built-in scene.
//
// 1. Tracer time per turn at 1 spp, 8 bounces (hybrid: rebuild + trace; pt: whole paths): of
//    the eye traced first and of the second, which reuses its paths (with reuse on the eyes
//    take turns to go first; off: left, right), median of --repeats frames, on and off
//    alternating; the share of the second eye's paths that reused the first's. Also, with
//    reuse on, the same frame traced again right after (warm): in a frame the first eye
//    finds the caches the G-buffer pass left (llvmpipe draws it on these cores), the second
//    the ones the first left; the warm trace shows the ratio without that difference.
// 2. Equal-time quality (hybrid): --frames frames with reuse off take a tracer time T; with
//    reuse on, frames are traced until their tracer time reaches T; --seeds times. Per-eye relMSE
//    and trimmed relMSE (core/error_metrics.h) of each mean against a converged pt reference
//    (harness/reference_cache.h, --reference-spp). Then reuse off again for as many frames
//    as reuse on got: off's trimmed relMSE at its frames over that at on's is what the frames
//    alone buy (1/N for a variance, less where a trimmed firefly tail or a bias floors it,
//    more or less where one count is a power of two, a whole Sobol net); the equal-time
//    figure over it is what reuse costs per frame. Then equal time again at 3/4 and 5/4 of
//    --frames, and the mean of the three counts' ratios: at 32, a whole Sobol net, off's
//    N x error on atrium is 5-15 % below that at 24, 38, 40, 51 and 62 frames, which lowered
//    that count's ratio by as much; the mean does not rest on one count.
// 3. The left's shadow answers (trace/stereo_reuse.h, "The approximations"): reuse on with
//    every reused sample tracing its own shadow ray instead (TraceSettings::
//    reusedOwnShadowRays), the same numbers: the second eye's tracer time, timed with the
//    others in 1, and the per-eye relMSE of the mean of --frames frames with the left's
//    answers against that mean (seed 1): what the approximation moves, against the relMSE
//    of the same mean against the reference.
// 4. Stereo consistency: the correlation of the two eyes' relative noise (relativeNoise) at
//    corresponding pixels (the right pixel's hit seen by the left pixel its projection lands
//    in, trace/stereo_reuse.h's partner test), one-frame images, on and off.
//
// Writes bench_stereo.csv to --out (out/bench).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "bench/bench_cli.h"
#include "core/builtin_scenes.h"
#include "core/error_metrics.h"
#include "core/huge_pages.h"
#include "core/stopwatch.h"
#include "core/view.h"
#include "gl/context.h"
#include "harness/reference_cache.h"
#include "hybrid/frame_settings.h"
#include "hybrid/hybrid_renderer.h"
#include "trace/caustics.h"
#include "trace/pixel_estimate.h"
#include "trace/sampling.h"

PHOTOVR_PREINIT(photovr::useHugePagesForMalloc);
namespace photovr {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

struct Args {
  std::string out;
  int width = 0, height = 0, repeats = 0, frames = 0, referenceSpp = 0, seeds = 0;
  bool caustics = kCausticsDefault;  // --caustics: both settings light-trace the sun's caustics
  bool equalFrames = false;  // reuse on gets off's frames: its error per frame, not per time
};

struct EyeTimes {
  // Median tracer time per turn: the eye traced first, then the second, which reuses its
  // paths (the eyes take turns, stereoTurnsOf); with reuse off, the left eye then the right.
  std::array<double, 2> ms{};
  double reusedShare = 0.0;     // the second eye's paths that reused the first's ...
  double ownBounceShare = 0.0;  // ... and of those, the ones that traced an own bounce too
};

// Equal-time quality at one frame count off (section 2 above), means over the seeds.
struct EqualTime {
  int framesOff = 0, framesOn = 0;       // per seed (on: the mean over seeds)
  double frameMsOff = 0, frameMsOn = 0;  // mean tracer time per frame
  std::array<double, 2> relMseOff{}, relMseOn{}, trimmedOff{}, trimmedOn{};
  std::array<double, 2> trimmedOffAtOn{};  // reuse off at on's frames (where measured)

  double ratio(int eye) const { return relMseOff[size_t(eye)] / relMseOn[size_t(eye)]; }
  double trimmedRatio(int eye) const { return trimmedOff[size_t(eye)] / trimmedOn[size_t(eye)]; }
};

struct Row {
  std::string scene;
  EyeTimes hybridOff, hybridOn, ptOn;
  std::array<double, 2> hybridWarmMs{};  // reuse on, the frame traced again right after
  double ownShadowSecondMs = 0.0;        // reuse on, own shadow rays: the second eye
  std::array<double, 2> shadowAnswerRelMse{}, shadowAnswerRefRelMse{};  // 3. above
  std::array<double, 2> ptOffMs{};
  // At --frames frames off, then (equal time only) at 3/4 and 5/4 of them.
  std::vector<EqualTime> equal;
  double correlationOff = 0.0, correlationOn = 0.0;
  size_t pairs = 0;
  bool equalFrames = false;  // Args::equalFrames
};

View viewOf(const Scene& scene) {
  View v;
  v.head = poseOf(scene.cameras.at(0));
  return v;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

TraceSettings settingsWith(const HybridRenderer& r, bool reuse, uint32_t seed = 0,
                           bool ownShadowRays = false) {
  TraceSettings s = r.traceContext().settings;
  s.stereoReuse = reuse;
  s.seed = seed;
  s.reusedOwnShadowRays = ownShadowRays;
  return s;
}

// Hybrid: tracer times per turn off, on and on with own shadow rays, alternating frame by
// frame.
void timeHybrid(HybridRenderer& r, const View& view, const Args& a, Row& row) {
  std::array<std::array<std::vector<double>, 2>, 3> ms;  // [off, on, own shadow rays][turn]
  std::array<std::vector<double>, 2> warm;               // [turn], reuse on
  std::array<gl::GBufferImage, 2> g;
  std::array<uint64_t, 3> paths{}, reused{}, ownBounces{};
  for (int k = -1; k < a.repeats; ++k)  // k = -1: warm-up of each
    for (int on = 0; on < 3; ++on) {
      r.setSettings(settingsWith(r, on > 0, 0, on == 2));
      FrameTimes t;
      const uint32_t f = uint32_t(std::max(k, 0));
      const auto eyes = eyeCameras(view, a.width, a.height, f, SamplerKind::Sobol);
      r.recycle(r.render(eyes, 2, f, &t));
      if (k < 0) continue;
      for (int e = 0; e < 2; ++e) ms[on][e].push_back(t.turnTraceMs[e]);
      if (on == 1) {  // the same G-buffer read back again, then the frame traced again
        FrameTimes w;
        r.readGBuffer(2, g, w);
        r.recycle(r.trace(g, eyes, 2, f, r.traceContext().settings, w, {}));
        for (int e = 0; e < 2; ++e) warm[e].push_back(w.turnTraceMs[e]);
      }
      paths[on] += t.turnPaths[1], reused[on] += t.turnReusedPaths[1];
      ownBounces[on] += t.turnOwnBounces[1];
    }
  for (int e = 0; e < 2; ++e) {
    row.hybridOff.ms[e] = median(ms[0][e]);
    row.hybridOn.ms[e] = median(ms[1][e]);
    row.hybridWarmMs[e] = median(warm[e]);
  }
  row.ownShadowSecondMs = median(ms[2][1]);
  row.hybridOn.reusedShare = double(reused[1]) / double(std::max<uint64_t>(paths[1], 1));
  row.hybridOn.ownBounceShare = double(ownBounces[1]) / double(std::max<uint64_t>(reused[1], 1));
}

// pt: both eyes traced as FramePipeline does, on and off alternating.
void timePt(const TraceContext& base, const View& view, const Args& a, Row& row) {
  StereoPaths paths;
  std::array<std::array<std::vector<double>, 2>, 2> ms;
  uint64_t total = 0, reused = 0;
  std::array<std::array<EyeImage, 2>, 2> buffers;  // per setting and eye, as FramePipeline keeps
  std::array<CausticPaths, 2> caustics;            // per setting: the eyes share a frame's
  TraceContext ctx = base;
  ctx.settings.reusedOwnShadowRays = false;  // the left's answers, as timeHybrid's 'on'
  for (int k = -1; k < a.repeats; ++k)
    for (int on = 0; on < 2; ++on) {
      const uint32_t f = uint32_t(std::max(k, 0));
      const auto eyes = eyeCameras(view, a.width, a.height, f, SamplerKind::Sobol);
      StereoTurns turns =
          stereoTurnsOf(on == 1, 2, f, paths, eyes[0], uint32_t(ctx.settings.samplesPerPixel));
      caustics[on].key.frame = ~0u;  // traced anew each frame (the warm-up repeats frame 0)
      for (StereoRole& role : turns.roles) role.caustics = &caustics[on];
      for (int turn = 0; turn < 2; ++turn) {
        const int e = turns.order[turn];
        const auto t0 = Clock::now();
        EyeImage& img = buffers[on][e];
        img = renderPathTraced(ctx, eyes[e], uint32_t(e), f, std::move(img), turns.roles[e]);
        if (k < 0) continue;
        ms[on][turn].push_back(msSince(t0));
        if (on && turn == 1) total += img.paths, reused += img.reusedPaths;
      }
    }
  for (int e = 0; e < 2; ++e) {
    row.ptOffMs[e] = median(ms[0][e]);
    row.ptOn.ms[e] = median(ms[1][e]);
  }
  row.ptOn.reusedShare = double(reused) / double(std::max<uint64_t>(total, 1));
}

// Frames of the hybrid with reuse 'on' until 'frames' of them (frames > 0) or until their
// tracer time reaches 'budgetMs'; the per-eye means, their count and tracer time.
struct Accumulated {
  std::array<std::vector<glm::vec3>, 2> mean;
  int frames = 0;
  double tracerMs = 0.0;
};
Accumulated accumulate(HybridRenderer& r, const View& view, const Args& a, bool on, int frames,
                       double budgetMs, uint32_t seed, bool ownShadowRays = false) {
  r.setSettings(settingsWith(r, on, seed, ownShadowRays));
  Accumulated acc;
  for (auto& m : acc.mean) m.assign(size_t(a.width) * a.height, glm::vec3(0.0f));
  while (frames > 0 ? acc.frames < frames : acc.tracerMs < budgetMs) {
    FrameTimes t;
    const uint32_t f = uint32_t(acc.frames);
    auto img = r.render(eyeCameras(view, a.width, a.height, f, SamplerKind::Sobol), 2, f, &t);
    acc.tracerMs += t.cpuMs();
    for (int e = 0; e < 2; ++e)
      for (size_t i = 0; i < acc.mean[e].size(); ++i) acc.mean[e][i] += img[e].color[i];
    r.recycle(std::move(img));
    ++acc.frames;
  }
  for (auto& m : acc.mean)
    for (glm::vec3& c : m) c /= float(acc.frames);
  return acc;
}

// Right pixel -> left pixel pairs that see one surface point, by primary rays through the
// pixel centres and the partner test of trace/stereo_reuse.h (roughness aside).
std::vector<std::pair<size_t, size_t>> correspondingPixels(const TraceContext& ctx,
                                                           const std::array<EyeCamera, 2>& eyes) {
  std::array<std::vector<SurfaceHit>, 2> hits;
  std::array<std::vector<bool>, 2> hit;
  for (int e = 0; e < 2; ++e) {
    const EyeCamera& c = eyes[e];
    hits[e].resize(size_t(c.width) * c.height);
    hit[e].assign(hits[e].size(), false);
    for (int y = 0; y < c.height; ++y)
      for (int x = 0; x < c.width; ++x) {
        const glm::vec3 dir = c.rayDirection(x + 0.5f, y + 0.5f);
        const TraceHit th =
            ctx.embree.intersect(c.pose.position, dir, 0.0f, kInfinity, RayRole::Camera);
        if (!th.hit) continue;
        const size_t i = size_t(y) * c.width + x;
        hits[e][i] = surfaceAt(ctx.scene, th.instance, th.triangle, th.b1, th.b2, dir);
        hit[e][i] = true;
      }
  }
  StereoPaths left;
  left.reset(eyes[0], 1);
  for (size_t i = 0; i < hits[0].size(); ++i)
    if (hit[0][i]) {
      FirstBounce& b = *left.slot(i, 0);
      b.position = hits[0][i].position, b.normal = hits[0][i].shadingNormal;
      b.instance = hits[0][i].instance;
    }
  std::vector<std::pair<size_t, size_t>> pairs;
  for (size_t i = 0; i < hits[1].size(); ++i) {
    if (!hit[1][i]) continue;
    SurfaceHit h = hits[1][i];
    h.bsdf.roughness = 1.0f;  // every surface point, whatever its material
    const EyeCamera& c = eyes[1];
    const glm::vec3 centreRay =
        c.rayDirection(float(i % c.width) + 0.5f, float(i / c.width) + 0.5f);
    if (const FirstBounce* b = findPartner(left, h, {c.pose.position, centreRay}))
      pairs.push_back({i, size_t(b - left.bounces.data())});
  }
  return pairs;
}

// Relative noise of a pixel, clipped: (frame - reference) / (reference + 0.01) on luminance,
// within +-3, so that a firefly (relative noise of 100 or more) does not decide the
// correlation alone.
double relativeNoise(const glm::vec3& value, const glm::vec3& reference) {
  const double r = luminance(reference);
  return std::clamp((luminance(value) - r) / (r + 0.01), -3.0, 3.0);
}

// Pearson correlation of the eyes' one-frame relative noise at corresponding pixels, over
// 'frames'.
double noiseCorrelation(HybridRenderer& r, const View& view, const Args& a, bool on,
                        const std::vector<std::pair<size_t, size_t>>& pairs,
                        const harness::Reference& ref) {
  r.setSettings(settingsWith(r, on));
  double sl = 0, sr = 0, sll = 0, srr = 0, slr = 0, n = 0;
  for (int k = 0; k < a.frames; ++k) {
    const uint32_t f = uint32_t(1000 + k);
    auto img = r.render(eyeCameras(view, a.width, a.height, f, SamplerKind::Sobol), 2, f, nullptr);
    for (const auto& [ri, li] : pairs) {
      const double nl = relativeNoise(img[0].color[li], ref.eyes[0][li]);
      const double nr = relativeNoise(img[1].color[ri], ref.eyes[1][ri]);
      sl += nl, sr += nr, sll += nl * nl, srr += nr * nr, slr += nl * nr, n += 1;
    }
    r.recycle(std::move(img));
  }
  const double cov = slr / n - sl / n * sr / n;
  const double vl = sll / n - sl / n * sl / n, vr = srr / n - sr / n * sr / n;
  return cov / std::sqrt(vl * vr);
}

// Equal time at 'frames' frames off (equal frames where a.equalFrames); 'offAtOn': also reuse
// off at on's frame count (section 2 above).
EqualTime measureEqualTime(HybridRenderer& r, const View& view, const Args& a,
                           const harness::Reference& ref, int frames, bool offAtOnToo) {
  EqualTime q;
  // Means over seeds: one caustic firefly can hold most of a 32-frame relMSE (spheres), so
  // one seed's ratio says little.
  for (int k = 0; k < a.seeds; ++k) {
    const uint32_t seed = uint32_t(k + 1);
    const Accumulated off = accumulate(r, view, a, false, frames, 0.0, seed);
    const Accumulated on = a.equalFrames ? accumulate(r, view, a, true, frames, 0.0, seed)
                                         : accumulate(r, view, a, true, 0, off.tracerMs, seed);
    q.framesOn += on.frames;
    q.frameMsOff += off.tracerMs / off.frames / a.seeds;
    q.frameMsOn += on.tracerMs / on.frames / a.seeds;
    for (int e = 0; e < 2; ++e) {
      q.relMseOff[e] += relMse(off.mean[e], ref.eyes[e]) / a.seeds;
      q.relMseOn[e] += relMse(on.mean[e], ref.eyes[e]) / a.seeds;
      q.trimmedOff[e] += trimmedRelMse(off.mean[e], ref.eyes[e]) / a.seeds;
      q.trimmedOn[e] += trimmedRelMse(on.mean[e], ref.eyes[e]) / a.seeds;
    }
    if (!offAtOnToo) continue;
    const Accumulated offAtOn = accumulate(r, view, a, false, on.frames, 0.0, seed);
    for (int e = 0; e < 2; ++e)
      q.trimmedOffAtOn[e] += trimmedRelMse(offAtOn.mean[e], ref.eyes[e]) / a.seeds;
  }
  q.framesOff = frames;
  q.framesOn = (q.framesOn + a.seeds / 2) / a.seeds;
  return q;
}

void measureQuality(HybridRenderer& r, const Scene& scene, const View& view, const Args& a,
                    Row& row) {
  const harness::Reference ref =
      harness::loadOrRenderReference({&scene, view, a.width, a.height, 8}, a.referenceSpp);
  row.equal.push_back(measureEqualTime(r, view, a, ref, a.frames, !a.equalFrames));
  if (!a.equalFrames)
    for (const int frames : {a.frames * 3 / 4, a.frames * 5 / 4})
      if (frames > 0) row.equal.push_back(measureEqualTime(r, view, a, ref, frames, false));
  const Accumulated answers = accumulate(r, view, a, true, a.frames, 0.0, 1);
  const Accumulated ownRays = accumulate(r, view, a, true, a.frames, 0.0, 1, true);
  for (int e = 0; e < 2; ++e) {
    row.shadowAnswerRelMse[e] = relMse(answers.mean[e], ownRays.mean[e]);
    row.shadowAnswerRefRelMse[e] = relMse(answers.mean[e], ref.eyes[e]);
  }
  const auto pairs = correspondingPixels(
      r.traceContext(), eyeCameras(view, a.width, a.height, 0, SamplerKind::Sobol));
  row.pairs = pairs.size();
  row.correlationOff = noiseCorrelation(r, view, a, false, pairs, ref);
  row.correlationOn = noiseCorrelation(r, view, a, true, pairs, ref);
}

// The mean over the frame counts of an eye's equal-time ratio (trimmed or not).
double meanRatio(const std::vector<EqualTime>& equal, int eye, bool trimmed) {
  double sum = 0.0;
  for (const EqualTime& q : equal) sum += trimmed ? q.trimmedRatio(eye) : q.ratio(eye);
  return sum / double(equal.size());
}

// Equal time's parts at --frames (section 2 above), then its figures at the other counts
// and the mean over all: a power of two (32) is a whole Sobol net, so off's error there is
// lower for its count than at most others (5-15 % on atrium), and one count alone is not
// the figure.
void printEqualTimeParts(const std::vector<EqualTime>& equal) {
  const EqualTime& q = equal.front();
  const std::array<double, 2> bought{q.trimmedOff[0] / q.trimmedOffAtOn[0],
                                     q.trimmedOff[1] / q.trimmedOffAtOn[1]};
  std::printf(
      "         reuse off at on's frames: trimmed off/off %.2f/%.2f, what the frames alone "
      "buy; trimmed on over it %.2f/%.2f, what reuse costs per frame\n",
      bought[0], bought[1], q.trimmedRatio(0) / bought[0], q.trimmedRatio(1) / bought[1]);
  std::printf("         equal time at other counts off:");
  for (size_t k = 1; k < equal.size(); ++k)
    std::printf(" %d frames (on %d) %.2f/%.2f, trimmed %.2f/%.2f;", equal[k].framesOff,
                equal[k].framesOn, equal[k].ratio(0), equal[k].ratio(1), equal[k].trimmedRatio(0),
                equal[k].trimmedRatio(1));
  std::printf(" mean of the %zu counts %.2f/%.2f, trimmed %.2f/%.2f\n", equal.size(),
              meanRatio(equal, 0, false), meanRatio(equal, 1, false), meanRatio(equal, 0, true),
              meanRatio(equal, 1, true));
}

void print(const Row& r, std::ofstream& csv) {
  const auto ratio = [](const std::array<double, 2>& ms) { return ms[1] / ms[0]; };
  std::printf(
      "%-8s hybrid tracer ms, first/second eye: off %6.1f/%6.1f, on %6.1f/%6.1f (second/first "
      "%.2f, reused %.3f, %.3f of those with an own bounce; traced again warm %.1f/%.1f, %.2f) "
      "| pt off %6.1f/%6.1f, on %6.1f/%6.1f (second/first %.2f, reused %.3f)\n",
      r.scene.c_str(), r.hybridOff.ms[0], r.hybridOff.ms[1], r.hybridOn.ms[0], r.hybridOn.ms[1],
      ratio(r.hybridOn.ms), r.hybridOn.reusedShare, r.hybridOn.ownBounceShare, r.hybridWarmMs[0],
      r.hybridWarmMs[1], ratio(r.hybridWarmMs), r.ptOffMs[0], r.ptOffMs[1], r.ptOn.ms[0],
      r.ptOn.ms[1], ratio(r.ptOn.ms), r.ptOn.reusedShare);
  const EqualTime& q = r.equal.front();
  std::printf(
      "         %s: off %d frames (%.1f ms each), on %d (%.1f ms); relMSE L/R off "
      "%.4f/%.4f, on %.4f/%.4f (off/on %.2f/%.2f); trimmed off/on %.2f/%.2f\n",
      r.equalFrames ? "equal frames" : "equal time", q.framesOff, q.frameMsOff, q.framesOn,
      q.frameMsOn, q.relMseOff[0], q.relMseOff[1], q.relMseOn[0], q.relMseOn[1], q.ratio(0),
      q.ratio(1), q.trimmedRatio(0), q.trimmedRatio(1));
  if (!r.equalFrames) printEqualTimeParts(r.equal);
  std::printf(
      "         the left's shadow answers: second eye %.1f ms with own shadow rays; relMSE "
      "L/R of %d frames against own rays %.2g/%.2g (against the reference %.4f/%.4f)\n",
      r.ownShadowSecondMs, q.framesOff, r.shadowAnswerRelMse[0], r.shadowAnswerRelMse[1],
      r.shadowAnswerRefRelMse[0], r.shadowAnswerRefRelMse[1]);
  std::printf(
      "         noise correlation of the eyes at %zu corresponding pixels: off %.3f, "
      "on %.3f\n",
      r.pairs, r.correlationOff, r.correlationOn);
  csv << r.scene << ',' << r.hybridOff.ms[0] << ',' << r.hybridOff.ms[1] << ',' << r.hybridOn.ms[0]
      << ',' << r.hybridOn.ms[1] << ',' << ratio(r.hybridOn.ms) << ',' << r.hybridOn.reusedShare
      << ',' << r.hybridOn.ownBounceShare << ',' << r.ptOffMs[0] << ',' << r.ptOffMs[1] << ','
      << r.ptOn.ms[0] << ',' << r.ptOn.ms[1] << ',' << ratio(r.ptOn.ms) << ',' << r.ptOn.reusedShare
      << ',' << q.framesOff << ',' << q.framesOn << ',' << q.relMseOff[0] << ',' << q.relMseOff[1]
      << ',' << q.relMseOn[0] << ',' << q.relMseOn[1] << ',' << q.trimmedOff[0] << ','
      << q.trimmedOff[1] << ',' << q.trimmedOn[0] << ',' << q.trimmedOn[1] << ','
      << r.correlationOff << ',' << r.correlationOn << ',' << r.hybridWarmMs[0] << ','
      << r.hybridWarmMs[1] << ',' << ratio(r.hybridWarmMs) << ',' << r.ownShadowSecondMs << ','
      << r.shadowAnswerRelMse[0] << ',' << r.shadowAnswerRelMse[1] << ','
      << r.shadowAnswerRefRelMse[0] << ',' << r.shadowAnswerRefRelMse[1] << ','
      << q.trimmedOffAtOn[0] << ',' << q.trimmedOffAtOn[1] << ',' << meanRatio(r.equal, 0, false)
      << ',' << meanRatio(r.equal, 1, false) << ',' << meanRatio(r.equal, 0, true) << ','
      << meanRatio(r.equal, 1, true) << '\n';
}

const char* const kUsage =
    "usage: photovr_bench_stereo [--out DIR] [--width W] [--height H] [--repeats N]\n"
    "                            [--frames F] [--seeds K] [--reference-spp S] [--scene NAME]\n"
    "                            [--equal-frames] [--caustics on|off]\n"
    "Stereo path reuse on against off on every built-in scene (or --scene), both eyes at\n"
    "W x H (120x135), 1 spp, 8 bounces: tracer times of the eye traced first and of the\n"
    "second (median of N, 7; the eyes take turns), hybrid and pt; the share of the second\n"
    "eye's paths reused; equal-time per-eye relMSE and trimmed relMSE (F frames off, 32,\n"
    "against as many as fit their tracer time on; means over K seeds, 4) against a pt\n"
    "reference of S spp (1024); the bias of the left's shadow answers (reused samples tracing\n"
    "their own shadow rays instead: time and relMSE); the correlation of the eyes' relative\n"
    "noise at corresponding pixels. Equal time also at 3F/4 and 5F/4 frames off, and the\n"
    "mean of the three. --equal-frames: reuse on gets the F frames off gets (its error per\n"
    "frame, not per time; F alone). --caustics on: both settings light-trace directional\n"
    "lights' caustics (trace/caustics.h; default on).\n"
    "Writes bench_stereo.csv to --out (out/bench).\n";

int run(const Options& o) {
  Args a;
  a.out = o.text("--out", "out/bench");
  a.width = o.integer("--width", 120, 8, 4096), a.height = o.integer("--height", 135, 8, 4096);
  a.repeats = o.integer("--repeats", 7, 1, 1000);
  a.frames = o.integer("--frames", 32, 2, 100000);
  a.seeds = o.integer("--seeds", 4, 1, 1000);
  a.referenceSpp = o.integer("--reference-spp", 1024, 1, 1 << 20);
  a.equalFrames = o.has("--equal-frames");
  a.caustics = o.choice("--caustics", kCausticsDefault ? "on" : "off", {"on", "off"}) == "on";
  const std::string only = o.has("--scene") ? builtinSceneArgument(o.text("--scene", "")) : "";
  const std::unique_ptr<gl::Context> gl = gl::Context::createHeadless();
  std::printf("bench_stereo: %dx%d x 2 eyes, 1 spp, 8 bounces; GL: %s\n", a.width, a.height,
              gl->renderer().c_str());
  std::filesystem::create_directories(a.out);
  std::ofstream csv(a.out + "/bench_stereo.csv");
  csv << "scene,hybrid_off_first_ms,hybrid_off_second_ms,hybrid_on_first_ms,hybrid_on_second_ms,"
         "hybrid_second_over_first,hybrid_reused_share,hybrid_own_bounce_share,pt_off_first_ms,"
         "pt_off_second_ms,pt_on_first_ms,pt_on_second_ms,pt_second_over_first,pt_reused_share,"
         "frames_off,frames_on,relmse_off_left,relmse_off_right,relmse_on_left,relmse_on_right,"
         "trimmed_off_left,trimmed_off_right,trimmed_on_left,trimmed_on_right,correlation_off,"
         "correlation_on,hybrid_on_warm_first_ms,hybrid_on_warm_second_ms,"
         "hybrid_warm_second_over_first,hybrid_own_shadow_rays_second_ms,"
         "shadow_answer_relmse_left,shadow_answer_relmse_right,"
         "shadow_answer_ref_relmse_left,shadow_answer_ref_relmse_right,"
         "trimmed_off_at_on_frames_left,trimmed_off_at_on_frames_right,"
         "equal_time_mean_left,equal_time_mean_right,"
         "trimmed_equal_time_mean_left,trimmed_equal_time_mean_right\n";
  for (const std::string& name : builtinSceneNames()) {
    if (!only.empty() && name != only) continue;
    const Scene scene = makeBuiltinScene(name);
    const View view = viewOf(scene);
    TraceSettings settings;
    settings.caustics = a.caustics;
    HybridRenderer renderer(scene, a.width, a.height, settings);
    Row row;
    row.scene = name;
    row.equalFrames = a.equalFrames;
    timeHybrid(renderer, view, a, row);
    timePt(renderer.traceContext(), view, a, row);
    measureQuality(renderer, scene, view, a, row);
    print(row, csv);
    std::fflush(stdout);
  }
  std::printf("wrote %s/bench_stereo.csv\n", a.out.c_str());
  return 0;
}

}  // namespace
}  // namespace photovr

int main(int argc, char** argv) {
  return photovr::benchMain(argc, argv, photovr::kUsage,
                            {"--out", "--width", "--height", "--repeats", "--frames",
                             "--reference-spp", "--scene", "--seeds", "--caustics"},
                            {"--equal-frames"}, photovr::run);
}
