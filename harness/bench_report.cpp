#include "harness/bench_report.h"

#include "harness/bench_format.h"
#include "hmd/headset_description.h"

#include <sys/utsname.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <thread>

namespace photovr::harness {

namespace {

std::string num(double v) {
  return formatNumber(v);
}

const ConfigResult* find(const std::vector<ConfigResult>& all, const std::string& scene,
                         bool (*match)(const BenchConfig&)) {
  for (const ConfigResult& r : all)
    if (r.config.scene == scene && r.config.scored && match(r.config)) return &r;
  return nullptr;
}

bool isBaseline(const BenchConfig& c) {
  return c.denoise == gl::DenoiseMode::Off && c.sampling == SampleMapKind::Uniform && c.spp == 1 &&
         c.threads == 0;
}

std::string cpuModel() {
  std::ifstream info("/proc/cpuinfo");
  for (std::string line; std::getline(info, line);)
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown CPU";
}

// Column order of both CSV files; bench/plot.gp reads them by number.
constexpr const char* kConfigColumns =
    "scene,mode,denoise,sampling,spp,bounces,threads,width,height";
constexpr const char* kFigureColumns =
    "gbuffer_ms,readback_ms,rebuild_ms,trace_ms,denoise_ms,frame_ms,mrays_s,relmse,psnr,ssim";

void writeConfigColumns(std::ostream& out, const BenchConfig& c) {
  out << c.scene << ',' << frameModeName(c.mode) << ',' << denoiseModeName(c.denoise) << ','
      << sampleMapKindName(c.sampling) << ',' << c.spp << ',' << c.bounces << ','
      << c.resolvedThreads() << ',' << c.width << ',' << c.height;
}

void writeFigureColumns(std::ostream& out, const FrameRecord& f) {
  out << num(f.gbufferMs) << ',' << num(f.readbackMs) << ',' << num(f.rebuildMs) << ','
      << num(f.traceMs) << ',' << num(f.denoiseMs) << ',' << num(f.frameMs) << ','
      << num(f.mraysPerSecond) << ',' << num(f.relMse) << ',' << num(f.psnr) << ',' << num(f.ssim);
}

// A configuration in one record: mean stage times and rates, the last frame's errors.
FrameRecord summaryRecord(const ConfigResult& r) {
  FrameRecord m = r.frames.back();
  for (double FrameRecord::*field :
       {&FrameRecord::gbufferMs, &FrameRecord::readbackMs, &FrameRecord::rebuildMs,
        &FrameRecord::traceMs, &FrameRecord::denoiseMs, &FrameRecord::frameMs,
        &FrameRecord::mraysPerSecond})
    m.*field = meanOf(r, field);
  return m;
}

}  // namespace

SceneSummary summarize(const std::string& scene, const std::vector<ConfigResult>& all) {
  SceneSummary s{scene};
  const ConfigResult* hybrid = find(all, scene, [](const BenchConfig& c) {
    return c.mode == FrameMode::Hybrid && isBaseline(c);
  });
  const ConfigResult* pt = find(all, scene, [](const BenchConfig& c) {
    return c.mode == FrameMode::PathTraced && isBaseline(c);
  });
  const ConfigResult* denoised = find(all, scene, [](const BenchConfig& c) {
    return c.mode == FrameMode::Hybrid && c.denoise == gl::DenoiseMode::Full &&
           c.sampling == SampleMapKind::Uniform && c.threads == 0;
  });
  for (const ConfigResult& r : all)
    if (r.config.scene == scene && r.config.width == hmd::HeadsetDescription::dk2().eyeWidth)
      s.dk2PeakRssMiB = std::max(s.dk2PeakRssMiB, r.peakRssMiB);
  if (hybrid && pt) {
    const FrameRecord& p = pt->frames[std::min<size_t>(16, pt->frames.size()) - 1];
    s.ptError = p.relMse, s.ptMs = p.elapsedMs;
    s.equalErrorTimeRatio = timeToError(hybrid->frames, s.ptError) / s.ptMs;
    s.equalTimeErrorRatio = errorAtTime(hybrid->frames, s.ptMs) / s.ptError;
    s.rawHybrid1 = hybrid->frames[0].relMse;
  }
  if (denoised) {
    s.denoised1 = denoised->frames[0].relMse, s.denoised1Ssim = denoised->frames[0].ssim;
    s.denoisedLast = denoised->frames.back().relMse;
  }
  return s;
}

std::string machineDescription(const std::string& glRenderer) {
  utsname u{};
  uname(&u);
  return cpuModel() + ", " + std::to_string(std::thread::hardware_concurrency()) +
         " hardware threads, GL " + glRenderer + ", " + u.sysname + " " + u.release +
         ", compiler " + __VERSION__;
}

void writeFrameCsv(const BenchReport& rep, const std::string& path) {
  std::ofstream out = openBenchOutput(path);
  out << "label," << kConfigColumns << ",frame,elapsed_ms,rays," << kFigureColumns << '\n';
  for (const ConfigResult& r : rep.configs)
    for (const FrameRecord& f : r.frames) {
      out << r.config.label() << ',';
      writeConfigColumns(out, r.config);
      out << ',' << f.frames << ',' << num(f.elapsedMs) << ',' << f.rays << ',';
      writeFigureColumns(out, f);
      out << '\n';
    }
}

void writeConfigCsv(const BenchReport& rep, const std::string& path) {
  std::ofstream out = openBenchOutput(path);
  out << "label,short," << kConfigColumns << ",frames,scored," << kFigureColumns
      << ",peak_rss_mib,rejected_samples\n";
  for (const ConfigResult& r : rep.configs) {
    out << r.config.label() << ',' << r.config.shortLabel() << ',';
    writeConfigColumns(out, r.config);
    out << ',' << r.config.frames << ',' << int(r.config.scored) << ',';
    writeFigureColumns(out, summaryRecord(r));
    out << ',' << num(r.peakRssMiB) << ',' << r.rejectedSamples << '\n';
  }
}

}  // namespace photovr::harness
