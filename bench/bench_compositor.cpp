// The headset compositor against the renderer (issue 6, "bench/"):
//  1. time of the compositor (gl/timewarp.h: re-projection + distortion + panel output in
//     one pass) vs the stereo G-buffer pass, both eyes at the same eye size in the same run
//     (target: compositor <= 1/4 of G-buffer), for a moved and a turned head, and of the
//     three-pass reference chain it replaced (grid re-projection, distortion, output);
//  2. the fraction of eye-buffer pixels the hidden-area mask skips (hmd/lens_maps.h);
//  3. lens-matched vs uniform sampling at equal perceived error: relMSE against a
//     converged reference, weighted per pixel by the lens density (display pixels per
//     eye-buffer pixel, hmd lensDensity), and the speed-up at equal weighted error
//     assuming error ~ 1 / tracer time (Monte Carlo; as `photovr ab` does).
// Prints tables and writes bench_compositor.csv, bench_compositor_mask.csv and
// bench_compositor_lens.csv to --out (default out/bench).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "display/compositor.h"
#include "gl/compositor.h"
#include "hmd/headset_description.h"
#include "bench/bench_cli.h"
#include "bench/pass_timing.h"
#include "core/builtin_scenes.h"
#include "core/error_metrics.h"
#include "core/huge_pages.h"
#include "core/stopwatch.h"
#include "gl/context.h"
#include "gl/gbuffer.h"
#include "gl/scene_gpu.h"
#include "hmd/lens_maps.h"
#include "hybrid/hybrid_renderer.h"
#include "hybrid/sample_maps.h"

PHOTOVR_PREINIT(photovr::useHugePagesForMalloc);
namespace photovr {
namespace {

struct Config {
  std::string out = "out/bench";
  int eyeW = kDk2EyeWidth, eyeH = kDk2EyeHeight, panelW = 1920, panelH = 1080;
  int repeats = 5;
  int lensW = 160, lensH = 180;  // sampling study: small, it needs a converged reference
  int uniformSpp = 4, referenceSpp = 64, referenceRounds = 4, trials = 3;
  bool samplingStudy = true;                              // --sampling 0: timing and mask only
  std::vector<std::string> scenes = builtinSceneNames();  // --scene NAME: one
};

std::array<EyeCamera, 2> sceneEyes(const Scene& s, int w, int h, glm::vec2 jitter) {
  return display::headEyes(poseOf(s.cameras.at(0)), StereoLayout::dk2(w, h), jitter);
}

// A small head turn (1.5 deg yaw, 1 cm): what a refresh re-projects over.
std::array<EyeCamera, 2> movedEyes(const Scene& s, int w, int h) {
  const Pose p = turnedHead(s, 1.5f, glm::vec3(0.01f, 0.0f, 0.0f));
  return display::headEyes(p, StereoLayout::dk2(w, h), glm::vec2(0.0f));
}

// What a pass shows at a pose against the truth there: the distortion chain on the G-buffer
// rendered at that pose (core/error_metrics.h panelDifference: 8-bit levels where both show
// something).
struct PoseError {
  std::string pose;
  PanelDifference stale;     // the frame as rendered at A, shown at B (no re-projection)
  PanelDifference timewarp;  // the compositor
  PanelDifference grid;      // the reference chain
  double disoccluded = 0;    // fraction of the lens-visible pixels the timewarp filled or left
};

struct Timing {
  std::string scene;
  std::vector<PoseError> errors;  // moved, turned
  PassTime gbuffer;
  PassTime timewarp, rotationOnly;  // the compositor (gl/timewarp.h), one pass
  PassTime asRendered;              // the same without re-projection
  PassTime floor;  // lens table, one depth fetch, three taps: any such pass's least cost
  PassTime gridReproject, distort, output;  // the reference chain it replaced
  PassTime chain() const { return gridReproject + distort + output; }
};

// The head turned only (no parallax): the timewarp's cheapest case, one depth fetch.
std::array<EyeCamera, 2> turnedEyes(const Scene& s, int w, int h) {
  return display::headEyes(turnedHead(s, 1.5f), StereoLayout::dk2(w, h), glm::vec2(0.0f));
}

Timing timeScene(const std::string& name, const Config& c) {
  const Scene scene = makeBuiltinScene(name);
  const gl::SceneGpu gpu(scene);
  gl::GBufferPass pass(c.eyeW, c.eyeH, gl::EyeRouting::Layered);
  display::Compositor comp(hmd::HeadsetDescription::dk2(), StereoLayout::dk2(c.eyeW, c.eyeH),
                           c.panelW, c.panelH, 90);
  const auto from = sceneEyes(scene, c.eyeW, c.eyeH, glm::vec2(0.0f));
  const auto to = movedEyes(scene, c.eyeW, c.eyeH);
  const auto turned = turnedEyes(scene, c.eyeW, c.eyeH);
  const std::array<glm::mat4, 2> vp = viewProjections(from);
  // The G-buffer's own layers stand in for a rendered frame: base colour as colour and
  // its D32F depth (the scene's real depth: the search's cost depends on its parallax).
  const unsigned color = pass.texture(gl::GBufferTarget::BaseColor), depth = pass.depthTexture();
  // The reference chain: grid re-projection (step 2), distortion, panel output.
  gl::ReprojectParams params;
  params.gridStep = 2;
  gl::Reprojector grid(c.eyeW, c.eyeH, params);
  gl::Distorter distorter(display::panelLens(hmd::HeadsetDescription::dk2(), c.panelW, c.panelH),
                          c.eyeW, c.eyeH,
                          {FovTangents::dk2LeftEye(), FovTangents::dk2LeftEye().mirrored()});
  const auto best = bestOfRounds(
      c.repeats,
      {[&] { pass.render(gpu, from, vp); },
       [&] {
         comp.run({color, depth}, from, to, 1.0f);
       },
       [&] {
         comp.run({color, depth}, from, turned, 1.0f);
       },
       [&] {
         comp.run({color, depth}, from, from, 1.0f, false);
       },
       [&] { grid.run(color, depth, from, to); }, [&] { distorter.run(grid.colorTexture()); },
       [&] { comp.output().run(distorter.panelTexture(), 1.0f); },
       [&] { comp.timewarp().runPanelFloor(color, depth, from, comp.output()); }});
  Timing t;
  t.scene = name;
  t.gbuffer = best[0], t.timewarp = best[1], t.rotationOnly = best[2], t.asRendered = best[3];
  t.gridReproject = best[4], t.distort = best[5], t.output = best[6], t.floor = best[7];
  const auto panelOf = [&](const std::array<EyeCamera, 2>& at) {
    pass.render(gpu, at, viewProjections(at));
    distorter.run(color);
    comp.output().run(distorter.panelTexture(), 1.0f);
    return comp.output().read();
  };
  for (const auto& [pose, to] : {std::pair{"moved", to}, std::pair{"turned", turned}}) {
    PoseError e;
    e.pose = pose;
    const auto truth = panelOf(to);
    panelOf(from);  // back to the frame at A
    comp.run({color, depth}, from, to, 1.0f);
    e.timewarp = panelDifference(comp.output().read(), truth);
    int disoccluded = 0, visible = 0;
    for (int eye = 0; eye < 2; ++eye) {
      const gl::ReprojectStats st = comp.timewarp().stats(eye);
      disoccluded += st.filled + st.uncovered;
      visible += st.reprojected + st.filled + st.uncovered;
    }
    e.disoccluded = double(disoccluded) / std::max(visible, 1);
    comp.run({color, depth}, from, from, 1.0f, false);
    e.stale = panelDifference(comp.output().read(), truth);
    grid.run(color, depth, from, to);
    distorter.run(grid.colorTexture());
    comp.output().run(distorter.panelTexture(), 1.0f);
    e.grid = panelDifference(comp.output().read(), truth);
    t.errors.push_back(e);
  }
  return t;
}

struct MaskRow {
  int eye;
  double hidden;
};

std::vector<MaskRow> hiddenFractions(const Config& c) {
  std::vector<MaskRow> rows;
  const hmd::LensModel lens;
  for (int e = 0; e < 2; ++e) {
    hmd::EyeBufferSpec spec;
    spec.eye = Eye(e);
    spec.fov = e == 0 ? FovTangents::dk2LeftEye() : FovTangents::dk2LeftEye().mirrored();
    spec.width = c.eyeW, spec.height = c.eyeH;
    const auto mask = hmd::hiddenAreaMask(lens, spec);
    rows.push_back({e, double(std::count(mask.begin(), mask.end(), 1)) / double(mask.size())});
  }
  return rows;
}

// ---------------------------------------------------------------------------------------
// Sampling study

// What an allocation of samples buys by the density map alone: with equal per-sample
// variance, the lens-weighted error of pixel i is w_i / n_i, so error x samples is
// (sum w_i / n_i) (sum n_i), constant for uniform scaling; each map's figure over that of
// maxSpp / 2 on every pixel the lens shows (hidden-area). > 1: better. spp proportional to
// sqrt(w) minimises it (Lagrange: d/dn_i of sum w_i / n_i + l n_i), spp proportional to w
// is lens-matched.
struct PredictedGain {
  double linear = 0, sqrt = 0;
};

PredictedGain predictedGain(const std::vector<float>& density, int maxSpp) {
  const float top = *std::max_element(density.begin(), density.end());
  const auto errorTimesSamples = [&](const std::function<double(double)>& spp) {
    double n = 0, e = 0;
    for (float w : density)
      if (w > 0.0f) {
        const double s = std::max(1.0, std::ceil(spp(w / top) - 1e-6));
        n += s, e += w / s;
      }
    return n * e;
  };
  const double uniform = errorTimesSamples([&](double) { return maxSpp / 2.0; });
  return {uniform / errorTimesSamples([&](double r) { return maxSpp * r; }),
          uniform / errorTimesSamples([&](double r) { return maxSpp * std::sqrt(r); })};
}

struct LensRow {
  std::string method;
  double meanSpp = 0, tracedFraction = 0, cpuMs = 0, error = 0;
  double cost() const { return cpuMs * error; }  // time x error: constant under MC
  // samples x error: the same without the clock (time is noisy on a loaded machine)
  double sampleCost() const { return meanSpp * error; }
};

std::array<std::vector<float>, 2> densityWeights(int w, int h) {
  std::array<std::vector<float>, 2> out;
  const hmd::LensModel lens;
  for (int e = 0; e < 2; ++e) {
    hmd::EyeBufferSpec spec;
    spec.eye = Eye(e);
    spec.fov = e == 0 ? FovTangents::dk2LeftEye() : FovTangents::dk2LeftEye().mirrored();
    spec.width = w, spec.height = h;
    out[e] = hmd::lensDensity(lens, spec);
  }
  return out;
}

// relMSE (eps 1e-2, as `photovr ab`) per pixel, weighted by the lens density.
double weightedError(const std::array<EyeImage, 2>& img,
                     const std::array<std::vector<glm::vec3>, 2>& ref,
                     const std::array<std::vector<float>, 2>& weight) {
  double sum = 0.0, wsum = 0.0;
  for (int e = 0; e < 2; ++e)
    for (size_t i = 0; i < ref[e].size(); ++i) {
      const glm::vec3 d = img[e].color[i] - ref[e][i];
      const glm::vec3 r = ref[e][i];
      const double rel = (d.x * d.x / (r.x * r.x + 1e-2) + d.y * d.y / (r.y * r.y + 1e-2) +
                          d.z * d.z / (r.z * r.z + 1e-2)) /
                         3.0;
      sum += weight[e][i] * rel;
      wsum += weight[e][i];
    }
  return sum / wsum;
}

// Hidden-area at the uniform count; lens-matched with its maximum twice the uniform count.
StereoSampleMaps sppMaps(SampleMapKind kind, const Config& c) {
  const int spp = kind == SampleMapKind::LensMatched ? 2 * c.uniformSpp : c.uniformSpp;
  return lensSampleMaps(kind, StereoLayout::dk2(c.lensW, c.lensH), spp);
}

std::vector<LensRow> lensStudy(const Config& c) {
  const Scene scene = makeBuiltinScene("cornell");
  TraceSettings settings;
  settings.samplesPerPixel = c.referenceSpp;
  HybridRenderer renderer(scene, c.lensW, c.lensH, settings);
  const auto eyes = sceneEyes(scene, c.lensW, c.lensH, samplePosition(SamplerKind::Sobol, 0));
  // Reference: every round the same jittered pixel positions (frame 0), new seeds.
  std::array<std::vector<glm::vec3>, 2> ref;
  for (int round = 0; round < c.referenceRounds; ++round) {
    renderer.setSeed(1000u + uint32_t(round));
    const auto img = renderer.render(eyes, 2, 0, nullptr);
    for (int e = 0; e < 2; ++e) {
      ref[e].resize(img[e].color.size());
      for (size_t i = 0; i < ref[e].size(); ++i)
        ref[e][i] += img[e].color[i] / float(c.referenceRounds);
    }
  }
  const auto weights = densityWeights(c.lensW, c.lensH);
  std::vector<LensRow> rows;
  for (const SampleMapKind kind :
       {SampleMapKind::Uniform, SampleMapKind::HiddenArea, SampleMapKind::LensMatched}) {
    const std::string method = sampleMapKindName(kind);
    TraceSettings ts;
    ts.samplesPerPixel = c.uniformSpp;
    HybridRenderer r(scene, c.lensW, c.lensH, ts);
    const StereoSampleMaps maps = sppMaps(kind, c);
    LensRow row;
    row.method = method;
    for (int t = 0; t < c.trials; ++t) {
      r.setSeed(uint32_t(t + 1));
      FrameTimes times;
      const auto img = r.render(eyes, 2, 0, &times, maps);
      row.cpuMs += times.cpuMs() / c.trials;
      row.error += weightedError(img, ref, weights) / c.trials;
      double spp = 0, traced = 0;
      for (int e = 0; e < 2; ++e)
        for (uint32_t n : img[e].samples) spp += n, traced += n > 0;
      row.meanSpp = spp / (2.0 * c.lensW * c.lensH);
      row.tracedFraction = traced / (2.0 * c.lensW * c.lensH);
    }
    rows.push_back(row);
  }
  return rows;
}

// The error each pass buys, per scene and head motion, printed and written to
// bench_compositor_error.csv.
void printErrors(const std::vector<Timing>& timings, const Config& c) {
  std::printf(
      "error at the new pose against the G-buffer rendered there (mean 8-bit levels over the "
      "panel pixels both show; black in one: %% of the panel):\n");
  std::printf("%-8s %-7s | %11s | %9s %11s %11s | %10s | %11s\n", "scene", "head", "as rendered",
              "timewarp", "disoccluded", "black in one", "grid chain", "black in one");
  std::ofstream csv(c.out + "/bench_compositor_error.csv");
  csv << "scene,head,shown_pixels,as_rendered_levels,timewarp_levels,timewarp_max_levels,"
         "disoccluded_fraction,timewarp_black_in_one,grid_chain_levels,grid_chain_black_in_one\n";
  const double panel = double(c.panelW) * c.panelH;
  for (const Timing& t : timings)
    for (const PoseError& e : t.errors) {
      std::printf("%-8s %-7s | %11.3f | %9.3f %10.2f%% %10.2f%% | %10.3f | %10.2f%%\n",
                  t.scene.c_str(), e.pose.c_str(), e.stale.meanLevels, e.timewarp.meanLevels,
                  100.0 * e.disoccluded, 100.0 * e.timewarp.blackInOne / panel, e.grid.meanLevels,
                  100.0 * e.grid.blackInOne / panel);
      csv << t.scene << ',' << e.pose << ',' << e.timewarp.shown << ',' << e.stale.meanLevels << ','
          << e.timewarp.meanLevels << ',' << e.timewarp.maxLevels << ',' << e.disoccluded << ','
          << e.timewarp.blackInOne << ',' << e.grid.meanLevels << ',' << e.grid.blackInOne << '\n';
    }
}

const char* const kUsage =
    "usage: photovr_bench_compositor [--out DIR] [--width W] [--height H] [--repeats N]\n"
    "                                [--trials N] [--sampling 0|1] [--scene NAME]\n"
    "The headset compositor against the G-buffer pass (both eyes at W x H, 960x1080, on a\n"
    "1920x1080 panel; best of --repeats, 5), the error each compositor pass buys at a new\n"
    "head pose, the hidden-area mask, and (--sampling 1, default) lens-matched against\n"
    "uniform sampling at equal lens-weighted error (--trials, 3). Writes bench_compositor*.csv\n"
    "to --out (out/bench).\n";

Config parse(const Options& o) {
  Config c;
  c.out = o.text("--out", c.out);
  c.eyeW = o.integer("--width", c.eyeW, 8, 4096);
  c.eyeH = o.integer("--height", c.eyeH, 8, 4096);
  c.repeats = o.integer("--repeats", c.repeats, 1, 1000);
  c.trials = o.integer("--trials", c.trials, 1, 1000);
  c.samplingStudy = o.integer("--sampling", 1, 0, 1) == 1;
  if (o.has("--scene")) c.scenes = {builtinSceneArgument(o.text("--scene", ""))};
  return c;
}

int run(const Options& options) {
  const Config c = parse(options);
  const std::unique_ptr<gl::Context> ctx = gl::Context::createHeadless();
  std::filesystem::create_directories(c.out);
  std::printf(
      "bench_compositor: eyes %dx%d x 2, panel %dx%d (rotation 90), best of %d rounds; GL: %s\n",
      c.eyeW, c.eyeH, c.panelW, c.panelH, c.repeats, ctx->renderer().c_str());
  std::printf("%-8s %9s | %-31s | %-20s | %-15s | %-36s | %-17s\n", "", "",
              "compositor (timewarp, one pass)", "no re-projection", "floor (taps)",
              "reference chain (grid step 2)", "by CPU time");
  std::printf("%-8s %9s | %9s %9s %11s | %11s %8s | %6s %8s | %8s %8s %8s %9s | %8s %8s\n", "scene",
              "gbuffer", "moved", "turned", "/gbuffer", "as rendered", "/gbuffer", "floor",
              "/gbuffer", "reproj", "distort", "output", "/gbuffer", "fused", "chain");
  std::ofstream csv(c.out + "/bench_compositor.csv");
  csv << "scene,eye_width,eye_height,panel_width,panel_height,gbuffer_ms,timewarp_ms,"
         "timewarp_rotation_only_ms,timewarp_over_gbuffer,grid_reproject_step2_ms,distort_ms,"
         "output_ms,chain_over_gbuffer,gbuffer_cpu_ms,timewarp_cpu_ms,chain_cpu_ms,"
         "timewarp_over_gbuffer_cpu,chain_over_gbuffer_cpu,as_rendered_ms,"
         "as_rendered_over_gbuffer,floor_ms,floor_over_gbuffer\n";
  std::vector<Timing> timings;
  for (const std::string& name : c.scenes) {
    const Timing& t = timings.emplace_back(timeScene(name, c));
    const double fused = t.timewarp.wall / t.gbuffer.wall, chain = t.chain().wall / t.gbuffer.wall;
    const double fusedCpu = t.timewarp.cpu / t.gbuffer.cpu,
                 chainCpu = t.chain().cpu / t.gbuffer.cpu;
    const double asRendered = t.asRendered.wall / t.gbuffer.wall;
    const double floorRatio = t.floor.wall / t.gbuffer.wall;
    std::printf(
        "%-8s %9.1f | %9.1f %9.1f %11.3f | %11.1f %8.3f | %6.1f %8.3f | %8.1f %8.1f %8.1f %9.3f | "
        "%8.3f %8.3f\n",
        name.c_str(), t.gbuffer.wall, t.timewarp.wall, t.rotationOnly.wall, fused,
        t.asRendered.wall, asRendered, t.floor.wall, floorRatio, t.gridReproject.wall,
        t.distort.wall, t.output.wall, chain, fusedCpu, chainCpu);
    csv << name << ',' << c.eyeW << ',' << c.eyeH << ',' << c.panelW << ',' << c.panelH << ','
        << t.gbuffer.wall << ',' << t.timewarp.wall << ',' << t.rotationOnly.wall << ',' << fused
        << ',' << t.gridReproject.wall << ',' << t.distort.wall << ',' << t.output.wall << ','
        << chain << ',' << t.gbuffer.cpu << ',' << t.timewarp.cpu << ',' << t.chain().cpu << ','
        << fusedCpu << ',' << chainCpu << ',' << t.asRendered.wall << ',' << asRendered << ','
        << t.floor.wall << ',' << floorRatio << '\n';
  }
  std::printf(
      "(ms, best of %d alternating rounds; moved: 1.5 deg yaw + 1 cm, turned: 1.5 deg yaw; as "
      "rendered: the frame at its own pose, the lens and display transform only; floor: the lens "
      "table, one depth fetch and three bilinear taps per pixel, the least any depth "
      "re-projecting lens pass costs here; target: compositor <= 0.25 x gbuffer)\n",
      c.repeats);
  printErrors(timings, c);
  std::ofstream mask(c.out + "/bench_compositor_mask.csv");
  mask << "eye,width,height,hidden_fraction\n";
  for (const MaskRow& m : hiddenFractions(c)) {
    std::printf("hidden-area mask, %s eye %dx%d: %.1f %% of the pixels skipped\n",
                m.eye ? "right" : "left", c.eyeW, c.eyeH, 100.0 * m.hidden);
    mask << (m.eye ? "right" : "left") << ',' << c.eyeW << ',' << c.eyeH << ',' << m.hidden << '\n';
  }
  const auto density = densityWeights(c.lensW, c.lensH);
  for (int maxSpp : {4, 16, 64}) {
    const PredictedGain g = predictedGain(density[0], maxSpp);
    std::printf(
        "predicted by the density alone (%dx%d, up to %d spp), lens-weighted error x samples "
        "against hidden-area: lens-matched %.3fx, spp ~ sqrt(density) %.3fx\n",
        c.lensW, c.lensH, maxSpp, g.linear, g.sqrt);
  }
  if (!c.samplingStudy) return 0;
  const std::vector<LensRow> rows = lensStudy(c);
  std::printf("sampling (cornell, %dx%d x 2 eyes, reference %d spp, mean of %d trials):\n", c.lensW,
              c.lensH, c.referenceSpp * c.referenceRounds, c.trials);
  std::printf("%-13s %9s %8s %10s %14s %14s %14s\n", "method", "mean spp", "traced", "tracer",
              "lens-wt relMSE", "speed-up/time", "/samples");
  std::ofstream lens(c.out + "/bench_compositor_lens.csv");
  lens << "method,mean_spp,traced_fraction,tracer_ms,lens_weighted_relmse,"
          "speedup_at_equal_error_by_time,speedup_at_equal_error_by_samples\n";
  for (const LensRow& r : rows) {
    const double byTime = rows[0].cost() / r.cost();
    const double bySamples = rows[0].sampleCost() / r.sampleCost();
    std::printf("%-13s %9.2f %7.1f%% %7.1f ms %14.5f %13.2fx %13.2fx\n", r.method.c_str(),
                r.meanSpp, 100.0 * r.tracedFraction, r.cpuMs, r.error, byTime, bySamples);
    lens << r.method << ',' << r.meanSpp << ',' << r.tracedFraction << ',' << r.cpuMs << ','
         << r.error << ',' << byTime << ',' << bySamples << '\n';
  }
  std::printf(
      "wrote %s/bench_compositor.csv, bench_compositor_error.csv, bench_compositor_mask.csv, "
      "bench_compositor_lens.csv\n",
      c.out.c_str());
  return 0;
}

}  // namespace
}  // namespace photovr

int main(int argc, char** argv) {
  return photovr::benchMain(
      argc, argv, photovr::kUsage,
      {"--out", "--width", "--height", "--repeats", "--trials", "--sampling", "--scene"}, {},
      photovr::run);
}
