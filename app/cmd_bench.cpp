// photovr bench: run time against error for every configuration of the bench matrix
// (app/bench_config.*) on the built-in scenes, with limit figures from the same run.
//
// Each configuration renders the same static camera's frame sequence (Halton jitter), and
// after every frame its image (the accumulated mean, or the denoiser's output) is scored
// against the cached converged reference: relMSE, PSNR, SSIM (core/perceptual_metrics.h).
// Outputs in --out: bench.csv (one row per frame), bench_configs.csv (one row per
// configuration), bench.json (machine, configurations, summary, limits), bench.md (the
// README "Performance" section) and, with gnuplot, bench_error_vs_time.png and
// bench_stages.png (bench/plot.gp).
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "app/bench_child.h"
#include "app/bench_config.h"
#include "app/bench_format.h"
#include "app/bench_report.h"
#include "app/commands.h"
#include "app/gl_context.h"
#include "core/files.h"
#include "core/options.h"
#include "app/reference_cache.h"
#include "core/builtin_scenes.h"
#include "core/error.h"
#include "core/scene_transform.h"

namespace photovr::app {
namespace {

const char* const kBenchHelp =
    "usage: photovr bench [--quick] [--scenes a,b] [--out DIR] [--backend B]\n"
    "Run time against error on the built-in scenes: hybrid and pt at 1 spp per frame, the\n"
    "denoised hybrid, lens-matched sampling, one tracer thread, and the DK2 eye resolution\n"
    "(timing and peak memory only), each scored per frame against a cached reference\n"
    "(relMSE, PSNR, SSIM). Also measures raw Embree on the tracer's rays and the empty GL\n"
    "frame and read-back. --quick: 120x135 per eye, 16 frames, 128-spp reference (under 5\n"
    "minutes on 2 cores once references are cached); default 240x270, 32 frames, 512 spp.\n"
    "Writes bench.csv, bench_configs.csv, bench.json, bench.md and (gnuplot) PNG plots into\n"
    "--out (default out/bench).\n";

std::vector<std::string> sceneList(const std::string& spec) {
  if (spec.empty()) return builtinSceneNames();
  std::vector<std::string> out;
  for (size_t b = 0; b <= spec.size();) {
    const size_t e = std::min(spec.find(',', b), spec.size());
    out.push_back(spec.substr(b, e - b));
    b = e + 1;
  }
  return out;
}

void printConfig(const ConfigResult& r) {
  const FrameRecord& last = r.frames.back();  // unscored configurations print "-"
  std::printf("%-54s %3d fr %8.1f ms/fr  relMSE %-8s SSIM %-6s %6.0f MiB\n",
              r.config.label().c_str(), r.config.frames, meanOf(r, &FrameRecord::frameMs),
              formatNumber(last.relMse, "%.4g", "-").c_str(),
              formatNumber(last.ssim, "%.4f", "-").c_str(), r.peakRssMiB);
  std::fflush(stdout);
}

// A built-in scene seen from its first camera, with its reference at the scored size.
struct LoadedScene {
  Scene scene;
  BenchScene bench;
  LoadedScene(const std::string& name, bool quick, bool withReference)
      : scene(makeBuiltinScene(name)) {
    bench.scene = &scene;
    bench.view.head = recenterOnView(scene, poseOf(scene.cameras.at(0)));
    bench.view.yfov = scene.cameras[0].yfov;
    if (!withReference) return;
    const BenchSize size = scoredSize(quick);
    bench.reference =
        loadOrRenderReference({&scene, bench.view, size.width, size.height, 8}, size.referenceSpp)
            .eyes;
  }
};

// Each configuration in its own process (app/bench_child.h): scene, GL context, renderer.
void runMatrix(const std::vector<BenchConfig>& matrix, bool quick, const std::string& backend,
               BenchReport& report) {
  for (const BenchConfig& c : matrix) {
    report.configs.push_back(runInChild(c, [&] {
      LoadedScene s(c.scene, quick, c.scored);
      auto context = createRenderContext(backend);
      return runConfig(c, s.bench, *context);
    }));
    printConfig(report.configs.back());
  }
}

// After the last child: the limit figures, in this process.
void measureLimits(const std::vector<std::string>& scenes, bool quick, const std::string& backend,
                   BenchReport& report) {
  auto context = createRenderContext(backend);
  report.glRenderer = context->renderer(), report.glVersion = context->version();
  const BenchSize size = scoredSize(quick);
  for (const std::string& name : scenes) {
    const LoadedScene s(name, quick, false);
    for (const TraceLimit& t : measureTraceLimits(s.bench, size.width, size.height, *context))
      report.traceLimits.push_back(t);
  }
  for (const auto& [w, h] : {std::pair{size.width, size.height}, {kDk2EyeWidth, kDk2EyeHeight}})
    report.glLimits.push_back(measureGlLimits(w, h, *context));
}

}  // namespace

int runBench(const Args& args) {
  if (wantsHelp(args)) {
    std::cout << kBenchHelp;
    return 0;
  }
  const Options o(args, {"--out", "--backend", "--scenes"}, {"--quick"});
  if (!o.positional().empty())
    throw UsageError("bench: unexpected argument '" + o.positional()[0] + "'");
  const auto t0 = std::chrono::steady_clock::now();
  BenchReport report;
  report.quick = o.has("--quick");
  const std::string dir = o.text("--out", "out/bench");
  createOutputFolder(dir);
  std::filesystem::create_directories(dir);
  const std::vector<std::string> scenes = sceneList(o.text("--scenes", ""));
  for (const std::string& s : scenes) makeBuiltinScene(s);  // unknown names fail up front
  const std::string backend = o.text("--backend", "");
  const std::vector<BenchConfig> matrix = benchMatrix(scenes, report.quick);
  std::printf("photovr bench%s: %zu configurations, each in its own process\n",
              report.quick ? " --quick" : "", matrix.size());
  runMatrix(matrix, report.quick, backend, report);
  measureLimits(scenes, report.quick, backend, report);
  report.machine = machineDescription(report.glRenderer);
  for (const std::string& name : scenes) report.scenes.push_back(summarize(name, report.configs));
  report.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  printSummary(report);
  writeFrameCsv(report, dir + "/bench.csv");
  writeConfigCsv(report, dir + "/bench_configs.csv");
  writeJson(report, dir + "/bench.json");
  writeMarkdown(report, dir + "/bench.md");
  plot(dir);
  std::printf("wrote %s/bench.csv, bench_configs.csv, bench.json, bench.md (%.0f s)\n", dir.c_str(),
              report.wallSeconds);
  return 0;
}

}  // namespace photovr::app
