#include "harness/bench_jobs.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "core/files.h"

namespace photovr::harness {
namespace {

const char* const kConfigMagic = "photovr-bench-job-1";
const char* const kLimitsMagic = "photovr-bench-limits-1";

// Every double with all its digits: the collected reports equal an in-process run's.
std::string exact(double v) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

std::string frameLine(const FrameRecord& f) {
  std::ostringstream o;
  o << f.frames;
  for (double v :
       {f.gbufferMs, f.readbackMs, f.rebuildMs, f.traceMs, f.denoiseMs, f.frameMs, f.elapsedMs})
    o << ' ' << exact(v);
  o << ' ' << f.rays;
  for (double v : {f.mraysPerSecond, f.relMse, f.psnr, f.ssim}) o << ' ' << exact(v);
  return o.str();
}

// strtod reads the "nan" that %.17g writes for unscored frames.
bool readDouble(std::istream& in, double& v) {
  std::string word;
  if (!(in >> word)) return false;
  char* end = nullptr;
  v = std::strtod(word.c_str(), &end);
  return end && *end == '\0';
}

bool readFrame(const std::string& line, FrameRecord& f) {
  std::istringstream in(line);
  if (!(in >> f.frames)) return false;
  for (double* v : {&f.gbufferMs, &f.readbackMs, &f.rebuildMs, &f.traceMs, &f.denoiseMs, &f.frameMs,
                    &f.elapsedMs})
    if (!readDouble(in, *v)) return false;
  if (!(in >> f.rays)) return false;
  for (double* v : {&f.mraysPerSecond, &f.relMse, &f.psnr, &f.ssim})
    if (!readDouble(in, *v)) return false;
  return true;
}

std::vector<BenchConfig> matrixOf(const BenchRequest& q) {
  return benchMatrix(q.scenes, q.quick, q.stereoReuse);
}

}  // namespace

std::string jobFile(const std::string& outDir, int index) {
  return outDir + "/jobs/job-" + std::to_string(index) + ".txt";
}

void writeConfigResult(const std::string& path, const ConfigResult& r, double seconds) {
  std::ostringstream o;
  o << kConfigMagic << ' ' << r.config.label() << ' ' << exact(r.peakRssMiB) << ' '
    << r.rejectedSamples << ' ' << r.frames.size() << ' ' << exact(seconds) << '\n';
  for (const FrameRecord& f : r.frames) o << frameLine(f) << '\n';
  writeFileAtomically(path, o.str());
}

std::optional<ConfigResult> readConfigResult(const std::string& path, const BenchConfig& config,
                                             double* seconds) {
  std::ifstream in(path);
  std::string line, magic, label;
  if (!std::getline(in, line)) return std::nullopt;
  std::istringstream h(line);
  ConfigResult r{config, {}, 0.0, 0};
  size_t frames = 0;
  double wall = 0.0;
  if (!(h >> magic >> label) || magic != kConfigMagic || label != config.label() ||
      !readDouble(h, r.peakRssMiB) || !(h >> r.rejectedSamples >> frames) || !readDouble(h, wall) ||
      frames == 0 || frames > 1000000)
    return std::nullopt;
  while (std::getline(in, line)) {
    FrameRecord f;
    if (!readFrame(line, f)) return std::nullopt;
    r.frames.push_back(f);
  }
  if (r.frames.size() != frames) return std::nullopt;
  if (seconds) *seconds = wall;
  return r;
}

void writeLimits(const std::string& path, const BenchReport& r) {
  std::ostringstream o;
  o << kLimitsMagic << '\n'
    << "renderer " << r.glRenderer << '\n'
    << "version " << r.glVersion << '\n'
    << "seconds " << exact(r.wallSeconds) << '\n';
  for (const TraceLimit& t : r.traceLimits)
    o << "trace " << t.scene << ' ' << t.mode << ' ' << t.rays << ' '
      << exact(t.photovrMraysPerSecond) << ' ' << exact(t.rawMraysPerSecond) << '\n';
  for (const GlLimit& g : r.glLimits)
    o << "gl " << g.width << ' ' << g.height << ' ' << exact(g.emptyFrameMs) << ' '
      << exact(g.readbackMs) << ' ' << exact(g.pboReadbackMs) << '\n';
  writeFileAtomically(path, o.str());
}

bool readLimits(const std::string& path, BenchReport& r) {
  std::ifstream in(path);
  std::string line;
  if (!std::getline(in, line) || line != kLimitsMagic) return false;
  BenchReport read;
  while (std::getline(in, line)) {
    std::istringstream l(line);
    std::string kind;
    l >> kind;
    if (kind == "renderer" || kind == "version") {
      std::string& field = kind == "renderer" ? read.glRenderer : read.glVersion;
      std::getline(l >> std::ws, field);
    } else if (kind == "seconds") {
      if (!readDouble(l, read.wallSeconds)) return false;
    } else if (kind == "trace") {
      TraceLimit t;
      if (!(l >> t.scene >> t.mode >> t.rays) || !readDouble(l, t.photovrMraysPerSecond) ||
          !readDouble(l, t.rawMraysPerSecond))
        return false;
      read.traceLimits.push_back(t);
    } else if (kind == "gl") {
      GlLimit g;
      if (!(l >> g.width >> g.height) || !readDouble(l, g.emptyFrameMs) ||
          !readDouble(l, g.readbackMs) || !readDouble(l, g.pboReadbackMs))
        return false;
      read.glLimits.push_back(g);
    } else {
      return false;
    }
  }
  r.glRenderer = read.glRenderer, r.glVersion = read.glVersion;
  r.wallSeconds += read.wallSeconds;
  r.traceLimits = read.traceLimits, r.glLimits = read.glLimits;
  return true;
}

std::vector<std::string> benchJobLabels(const BenchRequest& q) {
  std::vector<std::string> labels;
  for (const BenchConfig& c : matrixOf(q)) labels.push_back(c.label());
  labels.push_back("limits");
  return labels;
}

int runBenchJob(const BenchRequest& q, int index) {
  const std::vector<BenchConfig> matrix = matrixOf(q);
  if (index < 0 || size_t(index) > matrix.size())
    throw UsageError("--job: " + std::to_string(index) + " is not a job of this matrix (0.." +
                     std::to_string(matrix.size()) + ", see --list-jobs)");
  createOutputFolder(q.outDir + "/jobs");
  const std::string file = jobFile(q.outDir, index);
  const auto t0 = std::chrono::steady_clock::now();
  const auto seconds = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  if (size_t(index) == matrix.size()) {
    BenchReport report;
    report.quick = q.quick;
    measureBenchLimits(q.scenes, q.quick, q.backend, report);
    report.wallSeconds = seconds();
    writeLimits(file, report);
  } else {
    const ConfigResult r = runBenchConfig(matrix[size_t(index)], q.quick, q.backend);
    writeConfigResult(file, r, seconds());
  }
  std::printf("bench job %d (%s): wrote %s\n", index,
              size_t(index) == matrix.size() ? "limits" : matrix[size_t(index)].label().c_str(),
              file.c_str());
  return 0;
}

int collectBenchJobs(const BenchRequest& q) {
  const std::vector<BenchConfig> matrix = matrixOf(q);
  BenchReport report;
  report.quick = q.quick;
  std::vector<std::string> missing;
  for (size_t i = 0; i < matrix.size(); ++i) {
    double seconds = 0.0;
    if (std::optional<ConfigResult> r =
            readConfigResult(jobFile(q.outDir, int(i)), matrix[i], &seconds)) {
      report.configs.push_back(std::move(*r));
      report.wallSeconds += seconds;  // the jobs' own times: what one process would take
    } else
      missing.push_back(std::to_string(i) + " " + matrix[i].label());
  }
  if (!readLimits(jobFile(q.outDir, int(matrix.size())), report))
    missing.push_back(std::to_string(matrix.size()) + " limits");
  std::printf(
      "photovr bench --collect %s: %zu of %zu jobs finished; their own times add up to %.0f s\n",
      q.outDir.c_str(), matrix.size() + 1 - missing.size(), matrix.size() + 1, report.wallSeconds);
  for (const std::string& m : missing) std::printf("  missing: job %s\n", m.c_str());
  writeBenchReports(q, report);
  return missing.empty() ? 0 : 1;
}

}  // namespace photovr::harness
