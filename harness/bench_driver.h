// The bench harness's driver (photovr bench; app/cmd_bench.cpp parses its options): run
// time against error for every configuration of the bench matrix (harness/bench_config.*)
// on the built-in scenes, with limit figures from the same run.
//
// Each configuration renders the same static camera's frame sequence (Halton jitter), and
// after every frame its image (the accumulated mean, or the denoiser's output) is scored
// against the cached converged reference: relMSE, PSNR, SSIM (core/perceptual_metrics.h).
// Outputs in --out: bench.csv (one row per frame), bench_configs.csv (one row per
// configuration), bench.json (machine, configurations, summary, limits), bench.md (the
// README "Performance" section) and, with gnuplot, bench_error_vs_time.png and
// bench_stages.png (bench/plot.gp).
#pragma once

#include <string>
#include <vector>

#include "harness/bench_report.h"
#include "hybrid/frame_settings.h"

namespace photovr::harness {

struct BenchRequest {
  std::vector<std::string> scenes;  // built-in scene names
  bool quick = false;
  std::string outDir = "out/bench";
  std::string backend;  // empty: EGL, falling back to OSMesa
  bool stereoReuse = kStereoReuseDefault;
};

// "a,b" -> {"a", "b"}; empty -> every built-in scene.
std::vector<std::string> benchSceneList(const std::string& spec);

// Runs the matrix (each configuration in a child process), the limit figures, and writes
// the reports into outDir. Returns the exit status.
int runBenchMatrix(const BenchRequest& request);

// Its parts, which the jobs (harness/bench_jobs.h) run one at a time: one configuration in
// a child process (the calling process must not have started threads); the limit figures
// in this process; the reports from what a run gathered (its machine line, summaries,
// CSV, JSON, markdown, plots).
ConfigResult runBenchConfig(const BenchConfig& config, bool quick, const std::string& backend);
void measureBenchLimits(const std::vector<std::string>& scenes, bool quick,
                        const std::string& backend, BenchReport& report);
void writeBenchReports(const BenchRequest& request, BenchReport& report);

}  // namespace photovr::harness
