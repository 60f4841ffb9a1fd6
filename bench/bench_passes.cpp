// The whole-image passes outside the tracer (docs/MEASUREMENTS.md, "Serial passes left in
// the frame"): each as it ran before (one thread, as the code was at ba87019) and as it
// runs now, on the same images in the same run, at --width x --height (the DK2's eye,
// 960x1080) with --threads worker threads (all by default). The serial versions are kept
// here as the baselines; the frame no longer runs them.
//
// - clear: the recycled eye image zeroed before each eye was traced (now its tiles write
//   every plane themselves: nothing left to time);
// - accumulate: render's running mean of a frame into the sum (trace/trace_output.h);
// - denoise input: the unfiltered radiance for the denoiser, into fresh storage then, into
//   kept storage now (hybrid/denoise_input.h);
// - files: an eye's nine EXRs and a PNG, written one after another then, concurrently now
//   (core/image_io.h writeFiles), into --out/bench_passes_files (removed afterwards).
//
// Best of --repeats (5) rounds, old and new alternating within each, after a warm-up round. Writes
// bench_passes.csv to --out (out/bench).
#include <tbb/global_control.h>
#include <tbb/info.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "bench/bench_cli.h"
#include "bench/pass_timing.h"
#include "core/huge_pages.h"
#include "hybrid/denoise_input.h"
#include "trace/pixel_estimate.h"
#include "trace/trace_output.h"

PHOTOVR_PREINIT(photovr::useHugePagesForMalloc);
namespace photovr {
namespace {

struct Config {
  std::string out = "out/bench";
  int width = 960, height = 1080, repeats = 5, threads = 0;
};

// A traced-looking eye image: every plane filled, values varying per pixel.
EyeImage syntheticEye(int w, int h, float seed) {
  EyeImage img;
  allocateEyeImage(img, w, h);
  for (size_t i = 0; i < img.color.size(); ++i) {
    const float u = float(i % 977) / 977.0f + seed;
    const glm::vec3 v(u, 0.5f * u + 0.1f, 1.0f - 0.3f * u);
    img.color[i] = img.albedo[i] = img.normal[i] = img.diffuse[i] = img.specular[i] = v;
    img.diffuseAlbedo[i] = img.specularAlbedo[i] = v + 0.01f;
    img.depth[i] = 0.5f * u;
    img.samples[i] = 1;
  }
  return img;
}

// The passes as they ran before (one thread).
void serialClear(EyeImage& img) {
  const size_t n = img.color.size();
  for (auto* v : {&img.color, &img.albedo, &img.normal, &img.diffuse, &img.specular,
                  &img.diffuseAlbedo, &img.specularAlbedo, &img.guide})
    v->assign(n, glm::vec3(0.0f));
  img.depth.assign(n, 0.0f);
  img.samples.assign(n, 0);
}

void serialAccumulate(EyeImage& sum, const EyeImage& frame, int framesSoFar) {
  const float w = 1.0f / float(framesSoFar + 1);
  for (EyePlane plane : kAveragedPlanes) {
    std::vector<glm::vec3>& s = sum.*plane;
    const std::vector<glm::vec3>& f = frame.*plane;
    for (size_t i = 0; i < s.size(); ++i) s[i] += (f[i] - s[i]) * w;
  }
  for (size_t i = 0; i < sum.samples.size(); ++i) sum.samples[i] += frame.samples[i];
}

std::vector<glm::vec3> serialDenoiseInput(const EyeImage& img, bool& guided) {
  std::vector<glm::vec3> unfiltered(img.color.size());  // fresh storage, as each frame had
  guided = false;
  for (size_t i = 0; i < img.color.size(); ++i) {
    unfiltered[i] = img.color[i] - (img.diffuse[i] * img.diffuseAlbedo[i] +
                                    img.specular[i] * img.specularAlbedo[i]);
    guided |= !img.guide.empty() && img.guide[i] != glm::vec3(0.0f);
  }
  return unfiltered;
}

const char* const kUsage =
    "usage: photovr_bench_passes [--out DIR] [--width W] [--height H] [--repeats N]\n"
    "                            [--threads N]\n"
    "The whole-image passes outside the tracer, one eye at W x H (960x1080): the serial\n"
    "code they replaced against what runs now, with N worker threads (all by default), best\n"
    "of --repeats (5): clear, accumulate, denoise input, an eye's files. Writes\n"
    "bench_passes.csv to --out (out/bench).\n";

int run(const Options& o) {
  Config c;
  c.out = o.text("--out", c.out);
  c.width = o.integer("--width", c.width, 8, 8192);
  c.height = o.integer("--height", c.height, 8, 8192);
  c.repeats = o.integer("--repeats", c.repeats, 1, 1000);
  c.threads = o.integer("--threads", c.threads, 0, 1024);
  const int threads = c.threads > 0 ? c.threads : tbb::info::default_concurrency();
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
  std::filesystem::create_directories(c.out);
  const std::string dir = c.out + "/bench_passes_files";
  std::filesystem::create_directories(dir);

  EyeImage frame = syntheticEye(c.width, c.height, 0.0f),
           sum = syntheticEye(c.width, c.height, 0.2f);
  EyeImage cleared = syntheticEye(c.width, c.height, 0.4f);
  DenoiseInput kept;
  bool guided = false;
  fillDenoiseInput(frame, kept);  // its storage touched once, as a pipeline's is
  const std::vector<OutputFile> files = [&] {
    std::vector<OutputFile> f = eyeImageFiles(frame, dir);
    f.push_back({dir + "/color.png",
                 [&](const std::string& path) { writeImage(path, sideBySide({&frame}, 1.0f)); }});
    return f;
  }();

  // Old and new alternate within each round (bench/pass_timing.h), so a busy spell of the
  // shared machine falls on both.
  const std::vector<PassTime> t =
      bestOfRounds(c.repeats,
                   {[&] { serialClear(cleared); }, [&] { serialAccumulate(sum, frame, 3); },
                    [&] { accumulate(sum, frame, 3); }, [&] { serialDenoiseInput(frame, guided); },
                    [&] { fillDenoiseInput(frame, kept); },
                    [&] {
                      for (const OutputFile& f : files) f.write(f.path);
                    },
                    [&] { writeFiles(files); }},
                   [] {});
  struct Row {
    const char* pass;
    double serialMs, nowMs;
  };
  const std::vector<Row> rows = {{"clear", t[0].wall, 0.0},
                                 {"accumulate", t[1].wall, t[2].wall},
                                 {"denoise input", t[3].wall, t[4].wall},
                                 {"files", t[5].wall, t[6].wall}};
  std::filesystem::remove_all(dir);

  std::printf("bench_passes: one eye %dx%d, %d threads, best of %d\n", c.width, c.height, threads,
              c.repeats);
  std::printf("%-14s %12s %12s %8s\n", "pass", "serial ms", "now ms", "speedup");
  std::ofstream csv(c.out + "/bench_passes.csv");
  csv << "pass,width,height,threads,serial_ms,now_ms\n";
  for (const Row& r : rows) {
    if (r.nowMs > 0.0)
      std::printf("%-14s %12.2f %12.2f %7.1fx\n", r.pass, r.serialMs, r.nowMs,
                  r.serialMs / r.nowMs);
    else
      std::printf("%-14s %12.2f %12s %8s\n", r.pass, r.serialMs, "-", "gone");
    csv << r.pass << ',' << c.width << ',' << c.height << ',' << threads << ',' << r.serialMs << ','
        << r.nowMs << '\n';
  }
  std::printf(
      "(clear: gone, the tiles write every plane themselves; now_ms 0 in the CSV)\n"
      "wrote %s/bench_passes.csv\n",
      c.out.c_str());
  return 0;
}

}  // namespace
}  // namespace photovr

int main(int argc, char** argv) {
  return photovr::benchMain(argc, argv, photovr::kUsage,
                            {"--out", "--width", "--height", "--repeats", "--threads"}, {},
                            photovr::run);
}
