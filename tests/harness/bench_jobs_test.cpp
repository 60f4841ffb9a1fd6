// photovr bench as jobs (harness/bench_jobs.h): what a job writes is read back exactly, a
// file of another configuration or cut short is not taken, and collecting names the jobs
// that did not finish while writing the reports from those that did.
#include "harness/bench_jobs.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/files.h"
#include "tests/core/test_dir.h"

namespace photovr::harness {
namespace {

namespace fs = std::filesystem;

std::string freshDir() {
  const fs::path dir = testing::freshTestDir("photovr_bench_jobs");
  fs::create_directories(dir / "jobs");
  return dir.string();
}

// A configuration's result with awkward numbers: thirds (no short decimal), a NaN score
// (unscored frames), large counts.
ConfigResult sample(const BenchConfig& c, int frames) {
  ConfigResult r{c, {}, 123.0 / 3.0, 7};
  for (int f = 1; f <= frames; ++f) {
    FrameRecord rec;
    rec.frames = f;
    rec.gbufferMs = 1.0 / 3.0 * f, rec.traceMs = 10.0 / 7.0 * f, rec.frameMs = 2.0 * f;
    rec.elapsedMs = 2.0 * f * (f + 1) / 2;
    rec.rays = uint64_t(1) << (40 + f % 3);
    rec.mraysPerSecond = 3.25;
    rec.relMse = 0.1 / f, rec.psnr = 20.0 + std::log(double(f)), rec.ssim = FrameRecord::kNone;
    r.frames.push_back(rec);
  }
  return r;
}

TEST(BenchJobs, ConfigResultRoundTripsExactly) {
  const BenchRequest q{{"cornell"}, true, freshDir(), "", true};
  const std::vector<BenchConfig> matrix = benchMatrix(q.scenes, q.quick, q.stereoReuse);
  const ConfigResult r = sample(matrix[1], 5);
  const std::string file = jobFile(q.outDir, 1);
  writeConfigResult(file, r, 2.0 / 3.0);
  double seconds = 0.0;
  const std::optional<ConfigResult> back = readConfigResult(file, matrix[1], &seconds);
  ASSERT_TRUE(back);
  EXPECT_EQ(seconds, 2.0 / 3.0);
  EXPECT_EQ(back->peakRssMiB, r.peakRssMiB);
  EXPECT_EQ(back->rejectedSamples, r.rejectedSamples);
  ASSERT_EQ(back->frames.size(), r.frames.size());
  for (size_t i = 0; i < r.frames.size(); ++i) {
    const FrameRecord &a = r.frames[i], &b = back->frames[i];
    EXPECT_EQ(a.gbufferMs, b.gbufferMs);
    EXPECT_EQ(a.traceMs, b.traceMs);
    EXPECT_EQ(a.elapsedMs, b.elapsedMs);
    EXPECT_EQ(a.rays, b.rays);
    EXPECT_EQ(a.relMse, b.relMse);
    EXPECT_EQ(a.psnr, b.psnr);
    EXPECT_TRUE(std::isnan(b.ssim));
  }
  EXPECT_FALSE(readConfigResult(file, matrix[0])) << "another configuration's file";
  fs::resize_file(file, fs::file_size(file) - 10);
  EXPECT_FALSE(readConfigResult(file, matrix[1])) << "a file cut short";
}

TEST(BenchJobs, LimitsRoundTrip) {
  const std::string dir = freshDir();
  BenchReport r;
  r.glRenderer = "llvmpipe (LLVM 15.0.6, 256 bits)";
  r.glVersion = "4.5 (Core Profile) Mesa 22.3.6";
  r.traceLimits.push_back({"cornell", "hybrid", 12345, 4.0 / 3.0, 11.5});
  r.glLimits.push_back({120, 135, 0.7, 1.0 / 9.0, 0.25});
  writeLimits(dir + "/limits.txt", r);
  BenchReport back;
  ASSERT_TRUE(readLimits(dir + "/limits.txt", back));
  EXPECT_EQ(back.glRenderer, r.glRenderer);
  EXPECT_EQ(back.glVersion, r.glVersion);
  ASSERT_EQ(back.traceLimits.size(), 1u);
  EXPECT_EQ(back.traceLimits[0].photovrMraysPerSecond, 4.0 / 3.0);
  ASSERT_EQ(back.glLimits.size(), 1u);
  EXPECT_EQ(back.glLimits[0].readbackMs, 1.0 / 9.0);
}

// Two of cornell's six configurations and no limits: the reports hold those two, and the
// collector names the other five jobs and fails.
TEST(BenchJobs, CollectWritesWhatFinishedAndNamesTheRest) {
  BenchRequest q;
  q.scenes = {"cornell"};
  q.quick = true;
  q.outDir = freshDir();
  const std::vector<BenchConfig> matrix = benchMatrix(q.scenes, q.quick, q.stereoReuse);
  writeConfigResult(jobFile(q.outDir, 0), sample(matrix[0], 16), 1.5);
  writeConfigResult(jobFile(q.outDir, 1), sample(matrix[1], 16), 2.0);
  ::testing::internal::CaptureStdout();
  const int status = collectBenchJobs(q);
  const std::string out = ::testing::internal::GetCapturedStdout();
  EXPECT_EQ(status, 1);
  EXPECT_NE(out.find("2 of " + std::to_string(matrix.size() + 1) +
                     " jobs finished; their own times add up to 4 s"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("missing: job 2 " + matrix[2].label()), std::string::npos) << out;
  EXPECT_NE(out.find("missing: job " + std::to_string(matrix.size()) + " limits"),
            std::string::npos)
      << out;
  std::ifstream csv(q.outDir + "/bench_configs.csv");
  const std::string text((std::istreambuf_iterator<char>(csv)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find(matrix[0].label()), std::string::npos);
  EXPECT_NE(text.find(matrix[1].label()), std::string::npos);
  EXPECT_EQ(text.find(matrix[2].label()), std::string::npos);
}

}  // namespace
}  // namespace photovr::harness
