// Tracer throughput next to raw Embree on the same rays (issue 3, "In bench/").
//
// For each built-in scene and thread count: render one eye with the path tracer and time
// it (photovr rays/s = all rays it cast / render wall time), then replay exactly those rays
// (recorded by a RayRecorder on an untimed render) through bare rtcIntersect1 /
// rtcOccluded1 on the same Embree scene (EmbreeScene::replay) and time that. The ratio is
// the share of the tracer's time that traversal alone would take; the rest is primary ray
// setup, surface reconstruction, texture lookups, BSDF and light sampling. "raw nofl"
// replays the same rays on the scene with every filter removed, pricing the any-hit filters.
// The two floors replay them with the least shading a tracer does at each hit
// (bench/shading_floor.h): a Lambert toy's, and the same with photovr's own BSDF in its
// place. floor/raw is what a tracer that shades as little as that reaches; photovr/raw,
// what it does.
// Wall-clock numbers on a shared 2-core machine swing by +-30 %; compare runs with
// `perf stat -e task-clock taskset -c 0 ... --render-only --scene S` (CPU time) instead.
#include <tbb/global_control.h>
#include <tbb/info.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "bench/bench_cli.h"
#include "bench/shading_floor.h"
#include "core/builtin_scenes.h"
#include "core/huge_pages.h"
#include "core/camera.h"
#include "trace/path_tracer.h"

PHOTOVR_PREINIT(photovr::useHugePagesForMalloc);
namespace photovr {
namespace {

struct Config {
  std::string outDir = "out/bench";  // /out/ is git-ignored
  int width = 240, height = 270;     // a quarter of a DK2 eye per side: ~1 min for all rows
  int spp = 4;
  int repeats = 5;  // best of N timed runs: the least disturbed by the rest of the machine
  // One built-in scene or a .gltf/.glb file (profiling, A/B); empty: every built-in scene.
  std::string scene;
  bool renderOnly = false;  // no recording or replay: a profile then sees only the tracer
  BatchCall batchCall = BatchCall::Stream;  // how the wavefront tracer calls Embree
};

// The time a row keeps for a run it did not make (--render-only makes no replays).
constexpr double kUntimed = 1e30;

// Mrays/s of 'rays' in 'seconds', NaN where they were not timed: "nan" in the table and the
// CSV, and in the ratios taken of it, rather than a number.
double mraysOf(uint64_t rays, double seconds) {
  return seconds < kUntimed ? double(rays) / seconds * 1e-6
                            : std::numeric_limits<double>::quiet_NaN();
}

double msOf(double seconds) {
  return seconds < kUntimed ? seconds * 1e3 : std::numeric_limits<double>::quiet_NaN();
}

struct Row {
  std::string scene;
  int threads = 0;
  uint64_t intersectRays = 0, occludedRays = 0;
  double renderSeconds = 0, replaySeconds = 0, replayIntersectSeconds = 0,
         replayOccludedSeconds = 0, replayUnfilteredSeconds = 0, lambertFloorSeconds = 0,
         bsdfFloorSeconds = 0, buildMs = 0;
  uint64_t imageHash = 0;  // FNV-1a of the colour buffer: optimisations must keep it

  uint64_t rays() const { return intersectRays + occludedRays; }
  double photovrMrays() const { return mraysOf(rays(), renderSeconds); }
  double rawMrays() const { return mraysOf(rays(), replaySeconds); }
  double rawIntersectMrays() const { return mraysOf(intersectRays, replayIntersectSeconds); }
  double rawOccludedMrays() const { return mraysOf(occludedRays, replayOccludedSeconds); }
  double rawUnfilteredMrays() const { return mraysOf(rays(), replayUnfilteredSeconds); }
  double lambertFloorMrays() const { return mraysOf(rays(), lambertFloorSeconds); }
  double bsdfFloorMrays() const { return mraysOf(rays(), bsdfFloorSeconds); }
};

double seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

// Runs f and lowers 'best' to its wall time if it was faster.
template <typename F>
void timeBest(double& best, F&& f) {
  const auto t0 = std::chrono::steady_clock::now();
  f();
  best = std::min(best, seconds(t0));
}

uint64_t hashColors(const std::vector<glm::vec3>& c) {
  uint64_t h = 1469598103934665603ull;
  const auto* bytes = reinterpret_cast<const unsigned char*>(c.data());
  for (size_t i = 0; i < c.size() * sizeof(glm::vec3); ++i) h = (h ^ bytes[i]) * 1099511628211ull;
  return h;
}

// The intersect rays (the camera's among them) or the occluded ones.
std::vector<RecordedRay> ofKind(const std::vector<RecordedRay>& rays, bool occluded) {
  std::vector<RecordedRay> out;
  std::copy_if(rays.begin(), rays.end(), std::back_inserter(out), [&](const RecordedRay& r) {
    return (r.kind == RecordedRay::Kind::Occluded) == occluded;
  });
  return out;
}

// The scene with every material double-sided and opaque: Embree then has no filter function
// to call, so replaying the same rays on it prices the filters (the alpha mask's, and the
// camera rays' back-face culling). Its hits differ from the real scene's, so this is an
// estimate.
Scene withoutFilters(Scene scene) {
  for (Material& m : scene.materials) {
    m.doubleSided = true;
    m.alphaMode = AlphaMode::Opaque;
  }
  return scene;
}

// The recorded rays, split by kind, and the filter-free scene to replay them on.
struct Replays {
  std::vector<RecordedRay> all, intersect, occluded;
  const EmbreeScene& embree;
  Scene plainScene;
  std::unique_ptr<EmbreeScene> unfiltered;
  ShadingFloor floor;

  Replays(const Scene& scene, const EmbreeScene& e, std::vector<RecordedRay> rays)
      : all(std::move(rays)),
        intersect(ofKind(all, false)),
        occluded(ofKind(all, true)),
        embree(e),
        plainScene(withoutFilters(scene)),
        floor(scene) {
    if (!all.empty()) unfiltered = std::make_unique<EmbreeScene>(plainScene);
  }
};

// Each repeat times the render and every replay once, back to back, and each keeps its best:
// on a shared machine a busy spell then slows a render and its replays alike.
template <typename Render>
void timeAll(Row& row, Render&& render, const Replays& r, int repeats) {
  row.renderSeconds = row.replaySeconds = row.replayIntersectSeconds = row.replayOccludedSeconds =
      row.replayUnfilteredSeconds = row.lambertFloorSeconds = row.bsdfFloorSeconds = kUntimed;
  for (int k = 0; k < repeats; ++k) {
    timeBest(row.renderSeconds, render);
    if (r.all.empty()) continue;
    timeBest(row.replaySeconds, [&] { r.embree.replayParallel(r.all); });
    timeBest(row.replayIntersectSeconds, [&] { r.embree.replayParallel(r.intersect); });
    timeBest(row.replayOccludedSeconds, [&] { r.embree.replayParallel(r.occluded); });
    timeBest(row.replayUnfilteredSeconds, [&] { r.unfiltered->replayParallel(r.all); });
    timeBest(row.lambertFloorSeconds,
             [&] { r.embree.replayParallel(r.all, ShadingFloor::shadeLambert, &r.floor); });
    timeBest(row.bsdfFloorSeconds,
             [&] { r.embree.replayParallel(r.all, ShadingFloor::shadeBsdf, &r.floor); });
  }
}

Row measure(const std::string& name, const Scene& scene, int threads, const Config& opt) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
  Row row{name, threads};
  EmbreeScene embree(scene);
  row.buildMs = embree.stats().buildMilliseconds;
  const LightSet lights(scene);
  TraceSettings settings;
  settings.samplesPerPixel = opt.spp;
  settings.batchCall = opt.batchCall;
  const TraceContext ctx{scene, embree, lights, settings};
  StereoRig rig;
  rig.head = poseOf(scene.cameras.at(0));
  const EyeCamera cam =
      rig.eye(Eye::Left, opt.width, opt.height, samplePosition(SamplerKind::Sobol, 0));

  RayRecorder recorder;  // untimed render: records the rays and warms the caches
  embree.setRecorder(opt.renderOnly ? nullptr : &recorder);
  EyeImage img = renderPathTraced(ctx, cam, 0, 0);
  embree.setRecorder(nullptr);
  row.imageHash = hashColors(img.color);
  const Replays replays(scene, embree, recorder.take());
  if (!opt.renderOnly && replays.all.size() != img.rays)
    std::fprintf(stderr, "%s: recorded %zu rays, the tracer counted %llu\n", name.c_str(),
                 replays.all.size(), static_cast<unsigned long long>(img.rays));
  row.intersectRays = opt.renderOnly ? img.rays : replays.intersect.size();
  row.occludedRays = opt.renderOnly ? 0 : replays.occluded.size();
  timeAll(
      row, [&] { img = renderPathTraced(ctx, cam, 0, 0, std::move(img)); }, replays, opt.repeats);
  return row;
}

void printRow(const Row& r) {
  std::printf("%-8s %3d %9.2f %9.2f %9.2f %9.2f %9.2f %7.3f %7.3f %7.3f %9llu %8.1f %016llx\n",
              r.scene.c_str(), r.threads, r.photovrMrays(), r.rawMrays(), r.rawIntersectMrays(),
              r.rawOccludedMrays(), r.rawUnfilteredMrays(), r.lambertFloorMrays() / r.rawMrays(),
              r.bsdfFloorMrays() / r.rawMrays(), r.photovrMrays() / r.rawMrays(),
              static_cast<unsigned long long>(r.rays()), r.buildMs,
              static_cast<unsigned long long>(r.imageHash));
  std::fflush(stdout);
}

void writeCsv(const std::filesystem::path& file, const std::vector<Row>& rows) {
  std::ofstream out(file);
  out << "scene,threads,rays,intersect_rays,occluded_rays,photovr_mrays_s,raw_mrays_s,"
         "raw_intersect_mrays_s,raw_occluded_mrays_s,raw_unfiltered_mrays_s,ratio,render_ms,replay_"
         "ms,bvh_build_ms,"
         "image_hash,lambert_floor_mrays_s,bsdf_floor_mrays_s\n";
  for (const Row& r : rows) {
    char hash[17];
    std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(r.imageHash));
    out << r.scene << ',' << r.threads << ',' << r.rays() << ',' << r.intersectRays << ','
        << r.occludedRays << ',' << r.photovrMrays() << ',' << r.rawMrays() << ','
        << r.rawIntersectMrays() << ',' << r.rawOccludedMrays() << ',' << r.rawUnfilteredMrays()
        << ',' << r.photovrMrays() / r.rawMrays() << ',' << msOf(r.renderSeconds) << ','
        << msOf(r.replaySeconds) << ',' << r.buildMs << ',' << hash << ',' << r.lambertFloorMrays()
        << ',' << r.bsdfFloorMrays() << '\n';
  }
  if (!out) throw std::runtime_error("cannot write " + file.string());
}

const char* const kUsage =
    "usage: photovr_bench_trace [--out DIR] [--width W] [--height H] [--spp N] [--repeats N]\n"
    "                           [--scene NAME|FILE] [--render-only] [--batch stream|single]\n"
    "The tracer against bare rtcIntersect1/rtcOccluded1 on the rays it cast, one eye, per\n"
    "built-in scene, on 1 thread and all; writes bench_trace.csv to --out (out/bench).\n"
    "lamb, bsdf: the same rays with the least shading per hit, Lambert or photovr's BSDF\n"
    "(bench/shading_floor.h), against raw.\n"
    "--render-only: no recording or replay (for a profiler).\n"
    "--batch: the wavefront tracer's Embree calls, rtcIntersect1M/rtcOccluded1M streams (the\n"
    "default) or one rtcIntersect1/rtcOccluded1 per ray (what Embree 4 keeps).\n";

Config parse(const Options& o) {
  Config c;
  c.outDir = o.text("--out", c.outDir);
  c.width = o.integer("--width", c.width, 1, 4096);
  c.height = o.integer("--height", c.height, 1, 4096);
  c.spp = o.integer("--spp", c.spp, 1, 4096);
  c.repeats = o.integer("--repeats", c.repeats, 1, 1000);
  if (o.has("--scene")) c.scene = sceneArgument(o.text("--scene", ""));
  c.renderOnly = o.has("--render-only");
  const std::string call = o.text("--batch", "stream");
  if (call != "stream" && call != "single")
    throw std::runtime_error("--batch: expected stream or single, got '" + call + "'");
  c.batchCall = call == "single" ? BatchCall::Single : BatchCall::Stream;
  return c;
}

int run(const Config& opt) {
  const int all = tbb::info::default_concurrency();
  std::printf(
      "photovr_bench_trace: one eye %dx%d, %d spp, best of %d; raw = EmbreeScene::replay "
      "(bare rtcIntersect1/rtcOccluded1)\n",
      opt.width, opt.height, opt.spp, opt.repeats);
  std::printf("%-8s %3s %9s %9s %9s %9s %9s %7s %7s %7s %9s %8s %s\n", "scene", "thr", "photovr",
              "raw", "raw isec", "raw occl", "raw nofl", "floor", "floor", "ratio", "rays",
              "build ms", "image hash");
  std::printf("%-8s %3s %9s %9s %9s %9s %9s %7s %7s %7s\n", "", "", "Mrays/s", "Mrays/s", "Mrays/s",
              "Mrays/s", "Mrays/s", "lamb", "bsdf", "ph/raw");
  std::vector<Row> rows;
  for (const std::string& name : benchSceneNames(opt.scene)) {
    const Scene scene = loadBenchScene(name);
    if (scene.cameras.empty()) throw InputError(name, "the scene has no camera to render from");
    for (int threads : {1, all}) {
      rows.push_back(measure(name, scene, threads, opt));
      printRow(rows.back());
      if (all == 1) break;
    }
  }
  std::filesystem::create_directories(opt.outDir);
  const std::filesystem::path csv = std::filesystem::path(opt.outDir) / "bench_trace.csv";
  writeCsv(csv, rows);
  std::printf("wrote %s\n", csv.string().c_str());
  return 0;
}

}  // namespace
}  // namespace photovr

int main(int argc, char** argv) {
  return photovr::benchMain(
      argc, argv, photovr::kUsage,
      {"--out", "--width", "--height", "--spp", "--repeats", "--scene", "--batch"},
      {"--render-only"}, [](const photovr::Options& o) { return photovr::run(photovr::parse(o)); });
}
