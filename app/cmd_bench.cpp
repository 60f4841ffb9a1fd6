// photovr bench: the options of the bench harness (harness/bench_driver.h), which runs
// time against error for every configuration of its matrix.
#include <cstdio>
#include <iostream>

#include "app/commands.h"
#include "app/render_request.h"
#include "core/error.h"
#include "core/options.h"
#include "harness/bench_driver.h"
#include "harness/bench_jobs.h"

namespace photovr::app {
namespace {

const char* const kBenchHelp =
    "usage: photovr bench [--quick] [--scenes a,b] [--out DIR] [--backend B]\n"
    "Run time against error on the built-in scenes: hybrid and pt at 1 spp per frame, the\n"
    "denoised hybrid, lens-matched sampling, one tracer thread, and the DK2 eye resolution\n"
    "(timing and peak memory only), each scored per frame against a cached reference\n"
    "(relMSE, PSNR, SSIM). Also measures raw Embree on the tracer's rays and the empty GL\n"
    "frame and read-back. --quick: 120x135 per eye, 16 frames, 128-spp reference (under 5\n"
    "minutes on 2 cores once references are cached); default 240x270, 32 frames, 512 spp.\n"
    "Writes bench.csv, bench_configs.csv, bench.json, bench.md and (gnuplot) PNG plots into\n"
    "--out (default out/bench). --stereo-reuse on|off: every configuration's (default on;\n"
    "off labels its rows sr-off).\n"
    "As jobs for a scheduler (scripts/cluster/bench_parallel.sh, bench_slurm.sbatch):\n"
    "  --list-jobs            one line per job: index and configuration (the last: limits)\n"
    "  --job I                run job I alone into --out/jobs/\n"
    "  --collect DIR          write the reports into DIR from the jobs in DIR/jobs/ that\n"
    "                         finished, naming the missing ones (exit 1 if any)\n"
    "  (give every call the same --quick, --scenes and --stereo-reuse)\n";

}  // namespace

int runBench(const Args& args) {
  if (wantsHelp(args)) {
    std::cout << kBenchHelp;
    return 0;
  }
  const Options o(args, {"--out", "--backend", "--scenes", "--stereo-reuse", "--job", "--collect"},
                  {"--quick", "--list-jobs"});
  if (!o.positional().empty())
    throw UsageError("bench: unexpected argument '" + o.positional()[0] + "'");
  harness::BenchRequest request;
  request.quick = o.has("--quick");
  request.outDir = o.text("--out", "out/bench");
  request.scenes = harness::benchSceneList(o.text("--scenes", ""));
  request.backend = o.text("--backend", "");
  request.stereoReuse = parseStereoReuse(o);
  if (int(o.has("--list-jobs")) + int(o.has("--job")) + int(o.has("--collect")) > 1)
    throw UsageError("bench: --list-jobs, --job and --collect are one at a time");
  if (o.has("--list-jobs")) {
    const std::vector<std::string> labels = harness::benchJobLabels(request);
    for (size_t i = 0; i < labels.size(); ++i) std::printf("%zu\t%s\n", i, labels[i].c_str());
    return 0;
  }
  if (o.has("--job")) return harness::runBenchJob(request, o.integer("--job", 0, 0, 1 << 20));
  if (o.has("--collect")) {
    request.outDir = o.text("--collect", "");
    return harness::collectBenchJobs(request);
  }
  return harness::runBenchMatrix(request);
}

}  // namespace photovr::app
