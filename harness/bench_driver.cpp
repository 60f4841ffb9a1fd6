#include "harness/bench_driver.h"

#include <chrono>
#include <cstdio>
#include <filesystem>

#include "core/builtin_scenes.h"
#include "core/files.h"
#include "core/scene_transform.h"
#include "gl/render_context.h"
#include "harness/bench_child.h"
#include "harness/bench_config.h"
#include "harness/bench_format.h"
#include "harness/bench_report.h"
#include "harness/reference_cache.h"
#include "hmd/headset_description.h"

namespace photovr::harness {
namespace {

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

}  // namespace

// Each configuration in its own process (harness/bench_child.h): scene, GL context, renderer.
ConfigResult runBenchConfig(const BenchConfig& c, bool quick, const std::string& backend) {
  ConfigResult r = runInChild(c, [&] {
    LoadedScene s(c.scene, quick, c.scored);
    auto context = gl::createRenderContext(backend);
    return runConfig(c, s.bench, *context);
  });
  printConfig(r);
  return r;
}

// After the last child: the limit figures, in this process.
void measureBenchLimits(const std::vector<std::string>& scenes, bool quick,
                        const std::string& backend, BenchReport& report) {
  auto context = gl::createRenderContext(backend);
  report.glRenderer = context->renderer(), report.glVersion = context->version();
  const BenchSize size = scoredSize(quick);
  for (const std::string& name : scenes) {
    const LoadedScene s(name, quick, false);
    for (const TraceLimit& t : measureTraceLimits(s.bench, size.width, size.height, *context))
      report.traceLimits.push_back(t);
  }
  const hmd::HeadsetDescription dk2 = hmd::HeadsetDescription::dk2();
  for (const auto& [w, h] : {std::pair{size.width, size.height}, {dk2.eyeWidth, dk2.eyeHeight}})
    report.glLimits.push_back(measureGlLimits(w, h));
}

void writeBenchReports(const BenchRequest& q, BenchReport& report) {
  const std::string& dir = q.outDir;
  report.machine = machineDescription(report.glRenderer);
  for (const std::string& name : q.scenes) report.scenes.push_back(summarize(name, report.configs));
  printSummary(report);
  writeFrameCsv(report, dir + "/bench.csv");
  writeConfigCsv(report, dir + "/bench_configs.csv");
  writeJson(report, dir + "/bench.json");
  writeMarkdown(report, dir + "/bench.md");
  plot(dir);
  std::printf("wrote %s/bench.csv, bench_configs.csv, bench.json, bench.md (%.0f s)\n", dir.c_str(),
              report.wallSeconds);
}

std::vector<std::string> benchSceneList(const std::string& spec) {
  return sceneList(spec);
}

int runBenchMatrix(const BenchRequest& q) {
  const auto t0 = std::chrono::steady_clock::now();
  BenchReport report;
  report.quick = q.quick;
  const std::string& dir = q.outDir;
  createOutputFolder(dir);
  std::filesystem::create_directories(dir);
  for (const std::string& s : q.scenes) makeBuiltinScene(s);  // unknown names fail up front
  const std::vector<BenchConfig> matrix = benchMatrix(q.scenes, report.quick, q.stereoReuse);
  std::printf("photovr bench%s: %zu configurations, each in its own process\n",
              report.quick ? " --quick" : "", matrix.size());
  for (const BenchConfig& c : matrix)
    report.configs.push_back(runBenchConfig(c, q.quick, q.backend));
  measureBenchLimits(q.scenes, report.quick, q.backend, report);
  report.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  writeBenchReports(q, report);
  return 0;
}

}  // namespace photovr::harness
