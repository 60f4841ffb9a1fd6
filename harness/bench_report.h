// What `photovr bench` writes: per-frame and per-configuration CSV, JSON with the machine,
// a markdown summary for README "Performance", and the gnuplot plots (bench/plot.gp).
#pragma once

#include <string>
#include <vector>

#include "harness/bench_limits.h"
#include "harness/bench_run.h"

namespace photovr::harness {

// Hybrid against pt on one scene, from its baseline configurations (1 spp per frame).
struct SceneSummary {
  std::string scene;
  double ptError = 0, ptMs = 0;             // pt's relMSE after 16 frames (16 spp) and its time
  double equalErrorTimeRatio = 0;           // hybrid's time to reach ptError / ptMs (lower: better)
  double equalTimeErrorRatio = 0;           // hybrid's relMSE after ptMs / ptError (lower: better)
  double rawHybrid1 = 0;                    // relMSE of one 1-spp hybrid frame
  double denoised1 = 0, denoised1Ssim = 0;  // the same frame denoised (SVGF, no history)
  double denoisedLast = 0;                  // denoised after the last frame (with history)
  double dk2PeakRssMiB = 0;                 // largest peak over its DK2-resolution rows
};

struct BenchReport {
  bool quick = true;
  std::string machine;  // one line: CPU, cores, GL renderer, OS
  std::string glRenderer, glVersion;
  std::vector<ConfigResult> configs;
  std::vector<SceneSummary> scenes;
  std::vector<TraceLimit> traceLimits;
  std::vector<GlLimit> glLimits;
  double wallSeconds = 0;
};

SceneSummary summarize(const std::string& scene, const std::vector<ConfigResult>& configs);
std::string machineDescription(const std::string& glRenderer);

void writeFrameCsv(const BenchReport& r, const std::string& path);   // one row per frame
void writeConfigCsv(const BenchReport& r, const std::string& path);  // one row per config
void writeJson(const BenchReport& r, const std::string& path);
void writeMarkdown(const BenchReport& r, const std::string& path);
void printSummary(const BenchReport& r);

// Runs gnuplot on bench/plot.gp (looked up from the working folder, then beside the
// executable's parent); false with a message when gnuplot or the script is missing.
bool plot(const std::string& dir);

// Text describing the perceptual metric, for the JSON and the markdown.
extern const char* const kPerceptualMetricNote;

}  // namespace photovr::harness
