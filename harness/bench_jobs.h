// photovr bench as independent jobs for a scheduler (GNU parallel, a Slurm array): job I of
// the matrix runs one configuration (in a child process, as the whole bench does) and
// writes its frames to a file of its own in a shared folder; the last job measures the
// limit figures. Collecting assembles the reports from whatever jobs finished and names the
// ones missing. scripts/cluster/ has the recipes.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "harness/bench_driver.h"
#include "harness/bench_report.h"

namespace photovr::harness {

// One line per job: the matrix's configurations in order, then "limits".
std::vector<std::string> benchJobLabels(const BenchRequest& request);

// Runs job 'index' (0-based, as listed) into request.outDir/jobs/. Returns the exit status.
int runBenchJob(const BenchRequest& request, int index);

// Reads request.outDir/jobs/ and writes bench.csv, bench_configs.csv, bench.json, bench.md
// and the plots into request.outDir. Returns 0 when every job was there, 1 otherwise (the
// reports then hold what was).
int collectBenchJobs(const BenchRequest& request);

// The job files, exposed for tests: a configuration's result, and the limit figures with
// the GL renderer they were measured on. Written atomically; read back only when complete
// and of the same configuration.
std::string jobFile(const std::string& outDir, int index);
// 'seconds': the job's wall time (collected reports sum them: the serial time of the run).
void writeConfigResult(const std::string& path, const ConfigResult& result, double seconds);
std::optional<ConfigResult> readConfigResult(const std::string& path, const BenchConfig& config,
                                             double* seconds = nullptr);
void writeLimits(const std::string& path, const BenchReport& report);
bool readLimits(const std::string& path, BenchReport& report);

}  // namespace photovr::harness
