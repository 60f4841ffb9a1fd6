// bench.json: the machine, every configuration with its parameters and frames, the
// hybrid-against-pt summary per scene and the limit figures.
#include <ostream>

#include "harness/bench_format.h"
#include "harness/bench_report.h"

namespace photovr::harness {

const char* const kPerceptualMetricNote =
    "SSIM (Wang et al. 2004): 11x11 Gaussian window, sigma 1.5, K1 0.01, K2 0.03, on the "
    "display luminance (PBR Neutral, sRGB, Rec. 709 luma), mean of the two eyes. Chosen over "
    "FLIP because its closed form can be tested exactly and it needs no viewing distance, "
    "which a lens-distorted headset eye buffer does not have";

namespace {

std::string j(double v) {
  return formatNumber(v, "%.6g", "null");
}

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

void writeFrame(std::ostream& o, const FrameRecord& f) {
  o << "{\"frames\": " << f.frames << ", \"gbuffer_ms\": " << j(f.gbufferMs)
    << ", \"readback_ms\": " << j(f.readbackMs) << ", \"rebuild_ms\": " << j(f.rebuildMs)
    << ", \"trace_ms\": " << j(f.traceMs) << ", \"denoise_ms\": " << j(f.denoiseMs)
    << ", \"frame_ms\": " << j(f.frameMs) << ", \"elapsed_ms\": " << j(f.elapsedMs)
    << ", \"rays\": " << f.rays << ", \"mrays_per_s\": " << j(f.mraysPerSecond)
    << ", \"relmse\": " << j(f.relMse) << ", \"psnr\": " << j(f.psnr) << ", \"ssim\": " << j(f.ssim)
    << "}";
}

void writeConfig(std::ostream& o, const ConfigResult& r) {
  const BenchConfig& c = r.config;
  o << "    {\"label\": " << quoted(c.label()) << ", \"scene\": " << quoted(c.scene)
    << ", \"mode\": " << quoted(frameModeName(c.mode))
    << ", \"denoise\": " << quoted(gl::denoiseModeName(c.denoise))
    << ", \"sampling\": " << quoted(sampleMapKindName(c.sampling)) << ", \"spp\": " << c.spp
    << ", \"bounces\": " << c.bounces << ", \"threads\": " << c.resolvedThreads()
    << ", \"width\": " << c.width << ", \"height\": " << c.height
    << ", \"scored\": " << (c.scored ? "true" : "false")
    << ", \"peak_rss_mib\": " << j(r.peakRssMiB) << ", \"rejected_samples\": " << r.rejectedSamples
    << ",\n     \"frames\": [";
  for (size_t i = 0; i < r.frames.size(); ++i) {
    o << (i ? ",\n       " : "\n       ");
    writeFrame(o, r.frames[i]);
  }
  o << "]}";
}

void writeScene(std::ostream& o, const SceneSummary& s) {
  o << "    {\"scene\": " << quoted(s.scene) << ", \"pt_16spp_relmse\": " << j(s.ptError)
    << ", \"pt_16spp_ms\": " << j(s.ptMs)
    << ", \"hybrid_time_to_pt16_error_ratio\": " << j(s.equalErrorTimeRatio)
    << ", \"hybrid_error_at_pt16_time_ratio\": " << j(s.equalTimeErrorRatio)
    << ", \"hybrid_1spp_relmse\": " << j(s.rawHybrid1)
    << ", \"hybrid_1spp_denoised_relmse\": " << j(s.denoised1)
    << ", \"hybrid_1spp_denoised_ssim\": " << j(s.denoised1Ssim)
    << ", \"hybrid_denoised_last_frame_relmse\": " << j(s.denoisedLast)
    << ", \"dk2_peak_rss_mib\": " << j(s.dk2PeakRssMiB) << "}";
}

void writeLimits(std::ostream& o, const BenchReport& r) {
  o << "  \"limits\": {\n    \"trace\": [";
  for (size_t i = 0; i < r.traceLimits.size(); ++i) {
    const TraceLimit& t = r.traceLimits[i];
    o << (i ? ",\n      " : "\n      ") << "{\"scene\": " << quoted(t.scene)
      << ", \"mode\": " << quoted(t.mode) << ", \"rays\": " << t.rays
      << ", \"photovr_mrays_per_s\": " << j(t.photovrMraysPerSecond)
      << ", \"raw_embree_mrays_per_s\": " << j(t.rawMraysPerSecond)
      << ", \"efficiency\": " << j(t.efficiency()) << "}";
  }
  o << "],\n    \"gl\": [";
  for (size_t i = 0; i < r.glLimits.size(); ++i) {
    const GlLimit& g = r.glLimits[i];
    o << (i ? ",\n      " : "\n      ") << "{\"width\": " << g.width << ", \"height\": " << g.height
      << ", \"empty_gbuffer_frame_ms\": " << j(g.emptyFrameMs)
      << ", \"readback_ms\": " << j(g.readbackMs) << ", \"pbo_readback_ms\": " << j(g.pboReadbackMs)
      << "}";
  }
  o << "]\n  },\n";
}

}  // namespace

void writeJson(const BenchReport& r, const std::string& path) {
  std::ofstream o = openBenchOutput(path);
  o << "{\n  \"matrix\": " << quoted(r.quick ? "quick" : "full")
    << ",\n  \"machine\": " << quoted(r.machine) << ",\n  \"gl_renderer\": " << quoted(r.glRenderer)
    << ",\n  \"gl_version\": " << quoted(r.glVersion)
    << ",\n  \"wall_seconds\": " << j(r.wallSeconds)
    << ",\n  \"perceptual_metric\": " << quoted(kPerceptualMetricNote)
    << ",\n  \"relmse\": \"mean over pixels and channels of (x - r)^2 / (r^2 + 0.01)\""
    << ",\n  \"peak_rss\": \"VmHWM of a child process per configuration: scene, GL context, "
       "renderer, frames\""
    << ",\n  \"scenes\": [\n";
  for (size_t i = 0; i < r.scenes.size(); ++i) {
    writeScene(o, r.scenes[i]);
    o << (i + 1 < r.scenes.size() ? ",\n" : "\n");
  }
  o << "  ],\n";
  writeLimits(o, r);
  o << "  \"configs\": [\n";
  for (size_t i = 0; i < r.configs.size(); ++i) {
    writeConfig(o, r.configs[i]);
    o << (i + 1 < r.configs.size() ? ",\n" : "\n");
  }
  o << "  ]\n}\n";
}

}  // namespace photovr::harness
