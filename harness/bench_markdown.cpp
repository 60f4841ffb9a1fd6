// bench.md (the README "Performance" section, spliced in by bench/readme_performance.sh) and
// the summary printed at the end of a run.
#include <algorithm>
#include <cstdio>
#include <ostream>

#include "harness/bench_format.h"
#include "harness/bench_report.h"

namespace photovr::harness {
namespace {

std::string f(double v, const char* format) {
  return formatNumber(v, format, "-");
}

void sceneTable(std::ostream& o, const BenchReport& r) {
  o << "| scene | pt relMSE at 16 spp | equal error: hybrid time / pt time | equal time: "
       "hybrid relMSE / pt relMSE | hybrid 1 spp relMSE | 1 spp denoised relMSE (SSIM) | "
       "denoised after "
    << (r.configs.empty() ? 0 : r.configs.front().config.frames)
    << " frames | peak RSS at 960x1080 |\n|---|---|---|---|---|---|---|---|\n";
  for (const SceneSummary& s : r.scenes)
    o << "| " << s.scene << " | " << f(s.ptError, "%.4f") << " | "
      << f(s.equalErrorTimeRatio, "%.2f") << " | " << f(s.equalTimeErrorRatio, "%.2f") << " | "
      << f(s.rawHybrid1, "%.3f") << " | " << f(s.denoised1, "%.3f") << " ("
      << f(s.denoised1Ssim, "%.3f") << ") | " << f(s.denoisedLast, "%.4f") << " | "
      << f(s.dk2PeakRssMiB, "%.0f") << " MiB |\n";
}

void configTable(std::ostream& o, const BenchReport& r) {
  o << "| configuration | frames | frame ms | G-buffer | read-back | rebuild | trace | denoise | "
       "Mrays/s | relMSE | PSNR dB | SSIM | peak RSS MiB |\n"
       "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const ConfigResult& c : r.configs) {
    auto mean = [&](double FrameRecord::*field) { return meanOf(c, field); };
    const FrameRecord& last = c.frames.back();
    o << "| " << c.config.label() << " | " << c.config.frames << " | "
      << f(mean(&FrameRecord::frameMs), "%.1f") << " | " << f(mean(&FrameRecord::gbufferMs), "%.1f")
      << " | " << f(mean(&FrameRecord::readbackMs), "%.1f") << " | "
      << f(mean(&FrameRecord::rebuildMs), "%.1f") << " | " << f(mean(&FrameRecord::traceMs), "%.1f")
      << " | " << f(mean(&FrameRecord::denoiseMs), "%.1f") << " | "
      << f(mean(&FrameRecord::mraysPerSecond), "%.2f") << " | " << f(last.relMse, "%.4f") << " | "
      << f(last.psnr, "%.1f") << " | " << f(last.ssim, "%.3f") << " | " << f(c.peakRssMiB, "%.0f")
      << " |\n";
  }
}

void limitTables(std::ostream& o, const BenchReport& r) {
  o << "| scene | mode | rays | photovr Mrays/s | raw Embree Mrays/s | efficiency |\n"
       "|---|---|---|---|---|---|\n";
  for (const TraceLimit& t : r.traceLimits)
    o << "| " << t.scene << " | " << t.mode << " | " << t.rays << " | "
      << f(t.photovrMraysPerSecond, "%.2f") << " | " << f(t.rawMraysPerSecond, "%.2f") << " | "
      << f(t.efficiency(), "%.2f") << " |\n";
  o << "\n| eye size | empty G-buffer frame | read-back alone (sync) | read-back alone (PBO) |\n"
       "|---|---|---|---|\n";
  for (const GlLimit& g : r.glLimits)
    o << "| " << g.width << "x" << g.height << " | " << f(g.emptyFrameMs, "%.2f") << " ms | "
      << f(g.readbackMs, "%.2f") << " ms | " << f(g.pboReadbackMs, "%.2f") << " ms |\n";
}

}  // namespace

void writeMarkdown(const BenchReport& r, const std::string& path) {
  std::ofstream o = openBenchOutput(path);
  o << "Generated from `photovr bench" << (r.quick ? " --quick" : "") << "` ("
    << f(r.wallSeconds, "%.0f")
    << " s of bench time, summed over the jobs when collected) on: " << r.machine
    << ". Wall-clock figures on a shared 2-core machine vary by +-30 % between runs.\n\n"
    << "Hybrid against pt, 1 spp per frame, both eyes, scored against the cached converged "
       "reference; ratios below 1 favour the hybrid. Equal error: the time the hybrid needs to "
       "reach the relMSE pt reaches at 16 spp, over pt's time; equal time: the hybrid's relMSE "
       "after pt's 16-spp time, over pt's.\n\n";
  sceneTable(o, r);
  o << "\n![relMSE against time per configuration, log-log](docs/images/bench_error_vs_time.png)\n"
    << "![mean stage times per configuration](docs/images/bench_stages.png)\n\n"
    << "Every configuration (perceptual metric: " << kPerceptualMetricNote
    << "; peak RSS: the whole process, each configuration in a child process of its own):\n\n";
  configTable(o, r);
  o << "\nLimit figures from the same run: the tracer against bare `rtcIntersect1`/`rtcOccluded1` "
       "on the rays it cast (efficiency = photovr rays/s / raw rays/s), and the fixed GL "
       "cost:\n\n";
  limitTables(o, r);
}

void printSummary(const BenchReport& r) {
  std::printf("\nhybrid vs pt (ratios < 1 favour hybrid)\n%-8s %10s %12s %12s %10s %14s %10s\n",
              "scene", "pt16 relMSE", "equal-error", "equal-time", "1spp raw", "1spp denoised",
              "DK2 RSS");
  for (const SceneSummary& s : r.scenes)
    std::printf("%-8s %10.4f %12.2f %12.2f %10.3f %8.3f/%.3f %7.0f MiB\n", s.scene.c_str(),
                s.ptError, s.equalErrorTimeRatio, s.equalTimeErrorRatio, s.rawHybrid1, s.denoised1,
                s.denoised1Ssim, s.dk2PeakRssMiB);
  std::printf("\nlimits: tracer efficiency (photovr / raw Embree rays/s on the same rays)\n");
  for (const TraceLimit& t : r.traceLimits)
    std::printf("%-8s %-6s %8.2f / %8.2f Mrays/s = %.2f\n", t.scene.c_str(), t.mode.c_str(),
                t.photovrMraysPerSecond, t.rawMraysPerSecond, t.efficiency());
  for (const GlLimit& g : r.glLimits)
    std::printf("GL %dx%d: empty G-buffer frame %.2f ms, read-back alone %.2f ms (PBO %.2f ms)\n",
                g.width, g.height, g.emptyFrameMs, g.readbackMs, g.pboReadbackMs);
}

}  // namespace photovr::harness
