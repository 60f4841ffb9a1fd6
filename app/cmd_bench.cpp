// photovr bench: run time against error for hybrid and pt on the built-in scenes.
//
// For each scene both modes render the same frame sequence (1 spp per frame, Halton
// jitter, static camera); after 1, 2, 4, 8, 16 (32) frames the accumulated image is scored
// against the cached converged reference. Output: bench.csv (scene, mode, frames, ms,
// relMSE, PSNR), bench.json (machine and summary), and error_vs_time.png when gnuplot is
// installed. The summary gives, per scene, the time hybrid needs to reach the error pt
// reaches at 16 spp, divided by pt's time (lower is better), and peak RSS.
#include <sys/resource.h>

#include <chrono>
#include <filesystem>
#include <functional>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <thread>

#include "app/commands.h"
#include "app/gl_context.h"
#include "app/options.h"
#include "app/reference_cache.h"
#include "app/trace_output.h"
#include "core/builtin_scenes.h"
#include "core/error.h"
#include "core/error_metrics.h"
#include "core/scene_transform.h"
#include "hybrid/hybrid_renderer.h"

namespace photovr::app {
namespace {

using Clock = std::chrono::steady_clock;

struct Point {
  int frames = 0;
  double ms = 0.0, relMse = 0.0, psnr = 0.0;
};

double peakRssMiB() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_maxrss) / 1024.0;  // Linux reports KiB
}

std::vector<glm::vec3> joined(const std::vector<EyeImage>& eyes) {
  std::vector<glm::vec3> all;
  for (const EyeImage& e : eyes) all.insert(all.end(), e.color.begin(), e.color.end());
  return all;
}

// Accumulates 'frames' frames, scoring at every power of two.
std::vector<Point> curve(const std::function<std::array<EyeImage, 2>(uint32_t)>& frame, int frames,
                         int eyeCount, const std::vector<glm::vec3>& ref) {
  std::vector<Point> points;
  std::vector<EyeImage> sums(eyeCount);
  double ms = 0.0;
  for (int f = 0; f < frames; ++f) {
    const auto t0 = Clock::now();
    const auto out = frame(uint32_t(f));
    ms += std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    for (int e = 0; e < eyeCount; ++e) accumulate(sums[e], out[e], f);
    if (((f + 1) & f) == 0) {  // 1, 2, 4, 8, ...
      const auto img = joined(sums);
      points.push_back({f + 1, ms, relMse(img, ref), psnrDisplay(img, ref)});
    }
  }
  return points;
}

// Time the curve needs to reach 'error', by log-log interpolation between its points.
double timeToError(const std::vector<Point>& c, double error) {
  for (size_t i = 1; i < c.size(); ++i)
    if (c[i].relMse <= error) {
      const double t = (std::log(error) - std::log(c[i - 1].relMse)) /
                       (std::log(c[i].relMse) - std::log(c[i - 1].relMse));
      return std::exp(std::log(c[i - 1].ms) + t * (std::log(c[i].ms) - std::log(c[i - 1].ms)));
    }
  return c.back().ms * c.back().relMse / error;  // beyond the curve: relMSE ~ 1 / time
}

struct SceneResult {
  std::string name;
  std::vector<Point> hybrid, pt;
  double ratio = 0.0, rssMiB = 0.0;
};

SceneResult benchScene(const std::string& name, int w, int h, int frames, int refSpp,
                       const std::string& backend) {
  Scene scene = makeBuiltinScene(name);
  View view;
  view.head = recenterOnView(scene, poseOf(scene.cameras.at(0)));
  view.yfov = scene.cameras[0].yfov;
  const Reference ref = loadOrRenderReference({&scene, view, w, h, 8}, refSpp);
  std::vector<glm::vec3> refAll;
  for (const auto& e : ref.eyes) refAll.insert(refAll.end(), e.begin(), e.end());
  auto context = createRenderContext(backend);
  HybridRenderer renderer(scene, w, h, context->hasExtension("GL_ARB_shader_viewport_layer_array"),
                          TraceSettings{});
  auto cams = [&](uint32_t f) { return eyeCameras(view, w, h, f); };
  renderer.render(cams(0), 2, 0, nullptr);  // warm-up: shader compilation
  SceneResult r{name, {}, {}, 0.0, 0.0};
  r.hybrid =
      curve([&](uint32_t f) { return renderer.render(cams(f), 2, f, nullptr); }, frames, 2, refAll);
  r.pt = curve(
      [&](uint32_t f) {
        const auto eyes = cams(f);
        return std::array<EyeImage, 2>{renderPathTraced(renderer.traceContext(), eyes[0], 0, f),
                                       renderPathTraced(renderer.traceContext(), eyes[1], 1, f)};
      },
      frames, 2, refAll);
  const Point& pt16 = r.pt[std::min<size_t>(4, r.pt.size() - 1)];
  r.ratio = timeToError(r.hybrid, pt16.relMse) / pt16.ms;
  r.rssMiB = peakRssMiB();
  return r;
}

void writeOutputs(const std::vector<SceneResult>& results, const std::string& dir, int w, int h) {
  std::ofstream csv(dir + "/bench.csv");
  csv << "scene,mode,frames,ms,relmse,psnr\n";
  for (const SceneResult& r : results)
    for (const auto& [mode, c] : {std::pair{"hybrid", &r.hybrid}, {"pt", &r.pt}})
      for (const Point& p : *c)
        csv << r.name << ',' << mode << ',' << p.frames << ',' << p.ms << ',' << p.relMse << ','
            << p.psnr << '\n';
  std::ofstream json(dir + "/bench.json");
  json << "{\n  \"machine\": {\"threads\": " << std::thread::hardware_concurrency()
       << ", \"gl\": \"Mesa llvmpipe or as reported by the context\"},\n  \"eye\": [" << w << ", "
       << h << "],\n  \"scenes\": [\n";
  for (size_t i = 0; i < results.size(); ++i)
    json << "    {\"name\": \"" << results[i].name
         << "\", \"hybrid_time_to_pt16_error_ratio\": " << results[i].ratio
         << ", \"peak_rss_mib\": " << results[i].rssMiB << "}"
         << (i + 1 < results.size() ? ",\n" : "\n");
  json << "  ]\n}\n";
}

void plot(const std::vector<SceneResult>& results, const std::string& dir) {
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) {
    std::cout << "gnuplot not installed: no plot (bench.csv has the data)\n";
    return;
  }
  std::ofstream gp(dir + "/error_vs_time.gp");
  gp << "set terminal pngcairo size 900,600\nset output '" << dir << "/error_vs_time.png'\n"
     << "set logscale xy\nset xlabel 'time (ms)'\nset ylabel 'relMSE'\nset key outside\n"
     << "set datafile separator ','\nplot ";
  bool first = true;
  for (const SceneResult& r : results)
    for (const char* mode : {"hybrid", "pt"}) {
      gp << (first ? "" : ", ") << "'" << dir << "/bench.csv' using (strcol(2) eq '" << mode
         << "' && strcol(1) eq '" << r.name << "' ? $4 : 1/0):5 with linespoints title '" << r.name
         << " " << mode << "'";
      first = false;
    }
  gp << "\n";
  gp.close();
  if (std::system(("gnuplot " + dir + "/error_vs_time.gp").c_str()) == 0)
    std::cout << "wrote " << dir << "/error_vs_time.png\n";
}

}  // namespace

int runBench(const Args& args) {
  if (wantsHelp(args)) {
    std::cout << "usage: photovr bench [--quick] [--out DIR] [--backend B]\n"
                 "Run time against error of hybrid and pt on every built-in scene (1 spp per\n"
                 "frame, scored after 1, 2, 4, ... frames against a cached reference).\n"
                 "--quick: 120x135 per eye, 16 frames, 128-spp reference (a few minutes on\n"
                 "2 cores); default 240x270, 32 frames, 512-spp reference. Writes bench.csv,\n"
                 "bench.json and, with gnuplot, error_vs_time.png into --out (out/bench).\n";
    return 0;
  }
  const Options o(args, {"--out", "--backend"}, {"--quick"});
  if (!o.positional().empty())
    throw UsageError("bench: unexpected argument '" + o.positional()[0] + "'");
  const bool quick = o.has("--quick");
  const int w = quick ? 120 : 240, h = quick ? 135 : 270, frames = quick ? 16 : 32;
  const std::string dir = o.text("--out", "out/bench");
  std::filesystem::create_directories(dir);
  std::vector<SceneResult> results;
  std::printf("scene     hybrid time to pt's 16-spp error / pt time   peak RSS\n");
  for (const std::string& name : builtinSceneNames()) {
    results.push_back(benchScene(name, w, h, frames, quick ? 128 : 512, o.text("--backend", "")));
    std::printf("%-9s %8.2f                                    %6.0f MiB\n", name.c_str(),
                results.back().ratio, results.back().rssMiB);
  }
  writeOutputs(results, dir, w, h);
  plot(results, dir);
  std::cout << "wrote " << dir << "/bench.csv and bench.json\n";
  return 0;
}

}  // namespace photovr::app
