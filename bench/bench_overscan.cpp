// Overscan (core/camera.h StereoLayout): the eye buffers rendered a margin beyond the lens's
// field so that the compositor, re-projecting to a turned head, finds rendered pixels where
// it would otherwise leave the incoming strip black. What it costs and what it buys, per
// margin, on each built-in scene (or --scene):
//  - the eye buffers' pixels and the pixels traced (the hidden-area mask keeps only what a
//    turn within the margin can bring into the lens), relative to no overscan;
//  - the stereo G-buffer pass's time at that size (best of --repeats);
//  - for the head still and turned by 1.5 and 3 deg (yaw, and yaw + pitch): the share of the
//    panel the re-projected frame leaves black where a frame rendered at the new pose shows
//    something, and the mean error over the pixels both show (core/error_metrics.h). The
//    panel shows the lens's field whatever the margin (gl/timewarp.h setShownField), so the
//    truth is the frame rendered there without overscan.
// Prints a table and writes bench_overscan.csv to --out (default out/bench).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "display/compositor.h"
#include "gl/compositor.h"
#include "hmd/headset_description.h"
#include "bench/bench_cli.h"
#include "bench/pass_timing.h"
#include "core/builtin_scenes.h"
#include "core/error_metrics.h"
#include "core/huge_pages.h"
#include "gl/context.h"
#include "gl/gbuffer.h"
#include "gl/scene_gpu.h"
#include "hmd/lens_maps.h"

PHOTOVR_PREINIT(photovr::useHugePagesForMalloc);
namespace photovr {
namespace {

struct Config {
  std::string out = "out/bench";
  std::vector<std::string> scenes = builtinSceneNames();
  int fieldW = kDk2EyeWidth, fieldH = kDk2EyeHeight, panelW = 1920, panelH = 1080;
  int repeats = 3;
  std::vector<double> margins = {0, 1, 2, 3, 5};  // degrees
};

struct Turn {
  const char* name;
  float yawDeg, pitchDeg;
};
constexpr Turn kTurns[] = {{"still", 0.0f, 0.0f},
                           {"yaw 1.5", 1.5f, 0.0f},
                           {"yaw 3", 3.0f, 0.0f},
                           {"yaw+pitch 3", 2.12f, 2.12f}};  // 3 deg about a diagonal axis

struct TurnResult {
  double blackShare = 0;  // of the panel: shown at the new pose, black after re-projection
  double meanLevels = 0;  // over the pixels both show
};

struct Row {
  double marginDeg = 0;
  int width = 0, height = 0;
  double traced = 0;  // pixels the hidden-area mask keeps, both eyes
  PassTime gbuffer;
  std::vector<TurnResult> turns;
};

Pose turned(const Scene& s, const Turn& t) {
  Pose p = turnedHead(s, t.yawDeg);
  p.orientation =
      glm::normalize(p.orientation * glm::angleAxis(glm::radians(t.pitchDeg), glm::vec3(1, 0, 0)));
  return p;
}

double tracedPixels(const StereoLayout& l) {
  const hmd::LensModel lens;
  double n = 0;
  for (Eye e : {Eye::Left, Eye::Right}) {
    const hmd::EyeBufferSpec spec = hmd::EyeBufferSpec::of(l, e);
    const auto hidden = hmd::hiddenAreaMask(lens, spec);
    n += double(std::count(hidden.begin(), hidden.end(), uint8_t(0)));
  }
  return n;
}

// The panel at each turn, rendered there with the layout 'marginDeg' gives.
std::vector<std::vector<glm::u8vec4>> panelsAt(const Scene& scene, const gl::SceneGpu& gpu,
                                               double marginDeg, const Config& c) {
  const StereoLayout layout = StereoLayout::dk2(c.fieldW, c.fieldH, float(glm::radians(marginDeg)));
  gl::GBufferPass pass(layout.width, layout.height, gl::EyeRouting::Layered);
  display::Compositor comp(hmd::HeadsetDescription::dk2(), layout, c.panelW, c.panelH, 90);
  std::vector<std::vector<glm::u8vec4>> panels;
  for (const Turn& t : kTurns) {
    const auto at = display::headEyes(turned(scene, t), layout, glm::vec2(0.0f));
    pass.render(gpu, at, viewProjections(at));
    comp.run({pass.texture(gl::GBufferTarget::BaseColor), pass.depthTexture()}, at, at, 1.0f,
             false);
    panels.push_back(comp.output().read());
  }
  return panels;
}

Row measure(const Scene& scene, const gl::SceneGpu& gpu, double marginDeg, const Config& c,
            const std::vector<std::vector<glm::u8vec4>>& truth) {
  Row row;
  row.marginDeg = marginDeg;
  const StereoLayout layout = StereoLayout::dk2(c.fieldW, c.fieldH, float(glm::radians(marginDeg)));
  row.width = layout.width, row.height = layout.height;
  row.traced = tracedPixels(layout);
  gl::GBufferPass pass(layout.width, layout.height, gl::EyeRouting::Layered);
  display::Compositor comp(hmd::HeadsetDescription::dk2(), layout, c.panelW, c.panelH, 90);
  const unsigned color = pass.texture(gl::GBufferTarget::BaseColor), depth = pass.depthTexture();
  const auto from = display::headEyes(poseOf(scene.cameras.at(0)), layout, glm::vec2(0.0f));
  const auto render = [&](const std::array<EyeCamera, 2>& at) {
    pass.render(gpu, at, viewProjections(at));
  };
  row.gbuffer = bestOfRounds(c.repeats, {[&] { render(from); }})[0];
  const double panel = double(c.panelW) * c.panelH;
  render(from);
  for (size_t i = 0; i < std::size(kTurns); ++i) {
    const auto to = display::headEyes(turned(scene, kTurns[i]), layout, glm::vec2(0.0f));
    comp.run({color, depth}, from, to, 1.0f);
    const PanelDifference d = panelDifference(comp.output().read(), truth[i]);
    row.turns.push_back({d.blackInOne / panel, d.meanLevels});
  }
  return row;
}

void printRow(const std::string& scene, const Row& r, const Row& base, std::ostream& csv) {
  const double pixels = double(r.width) * r.height / (double(base.width) * base.height);
  std::printf("%-8s %4.1f   %4dx%-5d %6.3fx %6.3fx %6.1f ms", scene.c_str(), r.marginDeg, r.width,
              r.height, pixels, r.traced / base.traced, r.gbuffer.wall);
  csv << scene << ',' << r.marginDeg << ',' << r.width << ',' << r.height << ',' << pixels << ','
      << r.traced / base.traced << ',' << r.gbuffer.wall;
  for (const TurnResult& t : r.turns) {
    std::printf(" | %6.2f %% %6.3f     ", 100.0 * t.blackShare, t.meanLevels);
    csv << ',' << t.blackShare << ',' << t.meanLevels;
  }
  std::printf("\n");
  csv << '\n';
}

const char* const kUsage =
    "usage: photovr_bench_overscan [--out DIR] [--scene NAME] [--width W] [--height H]\n"
    "                              [--repeats N]\n"
    "Overscan margins 0, 1, 2, 3 and 5 deg on each built-in scene (or --scene NAME), eyes\n"
    "W x H over the lens's field (960x1080): buffer and traced pixels, the G-buffer's time\n"
    "(best of --repeats, 3), and for head turns of 1.5 and 3 deg the panel share the\n"
    "re-projected frame leaves black and its error. Writes bench_overscan.csv to --out\n"
    "(out/bench).\n";

int run(const Options& o) {
  Config c;
  c.out = o.text("--out", c.out);
  if (o.has("--scene")) c.scenes = {builtinSceneArgument(o.text("--scene", ""))};
  c.fieldW = o.integer("--width", c.fieldW, 8, 4096);
  c.fieldH = o.integer("--height", c.fieldH, 8, 4096);
  c.repeats = o.integer("--repeats", c.repeats, 1, 1000);
  const std::unique_ptr<gl::Context> ctx = gl::Context::createHeadless();
  std::filesystem::create_directories(c.out);
  std::printf("bench_overscan: field %dx%d per eye, panel %dx%d; GL: %s\n", c.fieldW, c.fieldH,
              c.panelW, c.panelH, ctx->renderer().c_str());
  std::printf("%-8s %-6s %-10s %7s %7s %9s", "scene", "margin", "eye buffer", "pixels", "traced",
              "gbuffer");
  for (const Turn& t : kTurns) std::printf(" | %-11s black, err", t.name);
  std::printf("\n");
  std::ofstream csv(c.out + "/bench_overscan.csv");
  csv << "scene,margin_deg,eye_width,eye_height,pixels_rel,traced_rel,gbuffer_ms";
  for (const char* t : {"still", "yaw15", "yaw3", "diag3"})
    csv << ',' << t << "_black_share," << t << "_mean_levels";
  csv << '\n';
  for (const std::string& name : c.scenes) {
    const Scene scene = makeBuiltinScene(name);
    const gl::SceneGpu gpu(scene);
    const auto truth = panelsAt(scene, gpu, 0.0, c);
    std::vector<Row> rows;
    for (double m : c.margins) {
      const Row& r = rows.emplace_back(measure(scene, gpu, m, c, truth));
      printRow(name, r, rows.front(), csv);
    }
  }
  std::printf(
      "(black: share of the panel a frame rendered at the new pose shows and the re-projected "
      "one leaves black; err: mean 8-bit levels where both show; pixels and traced relative to "
      "no margin)\nwrote %s/bench_overscan.csv\n",
      c.out.c_str());
  return 0;
}

}  // namespace
}  // namespace photovr

int main(int argc, char** argv) {
  return photovr::benchMain(argc, argv, photovr::kUsage,
                            {"--out", "--scene", "--width", "--height", "--repeats"}, {},
                            photovr::run);
}
