// The cost of an animated frame against a static one (issue 23): every built-in scene with
// every instance turning on its own node (the worst case for the top level: all of it
// moves), and Cornell with a skinned grid of --grid^2 vertices bent by two joints (CPU
// linear-blend skinning, the mesh BVH refit, the GL vertex upload). Hybrid, both eyes at
// W x H, 1 spp, 8 bounces, sequential frames through the frame pipeline; mean of --frames
// frames after one untimed warm-up. Writes bench_animation.csv.

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "bench/bench_cli.h"
#include "core/animation.h"
#include "core/builtin_scenes.h"
#include "core/huge_pages.h"
#include "core/mesh_gen.h"
#include "core/stopwatch.h"
#include "gl/context.h"
#include "hybrid/frame_pipeline.h"

PHOTOVR_PREINIT(photovr::useHugePagesForMalloc);
namespace photovr {
namespace {

// Every instance on a TRS child of a matrix parent (its placement), turning about y through
// a full turn in 4 s.
void turnEveryInstance(Scene& s) {
  Animation turn;
  turn.name = "turn";
  for (size_t k = 0; k < s.instances.size(); ++k) {
    AnimationChannel c;
    c.node = addAnimatableNode(s, int(k));
    c.path = AnimationPath::Rotation;
    for (int key = 0; key <= 4; ++key) {
      const float half = 0.25f * float(M_PI) * float(key);  // half the angle: key x 90 degrees
      c.times.push_back(float(key));
      c.values.emplace_back(0.0f, std::sin(half), 0.0f, std::cos(half));
    }
    turn.channels.push_back(c);
  }
  s.animations.push_back(turn);
}

// A grid of n x n vertices, 1.2 m square, standing in the box, on two joints blended across
// its width; the second joint swings +-30 degrees about z over 2 s.
void addSkinnedGrid(Scene& s, int n) {
  Mesh grid = makeQuad({-0.6f, 0.2f, 0.0f}, {1.2f, 0, 0}, {0, 1.2f, 0});
  grid.positions.clear(), grid.normals.clear(), grid.uv0.clear(), grid.indices.clear();
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const float u = float(x) / float(n - 1), v = float(y) / float(n - 1);
      grid.positions.emplace_back(-0.6f + 1.2f * u, 0.2f + 1.2f * v, 0.0f);
      grid.normals.emplace_back(0, 0, 1);
      grid.uv0.emplace_back(u, v);
      grid.skinning.joints.emplace_back(0, 1, 0, 0);
      grid.skinning.weights.emplace_back(1.0f - u, u, 0.0f, 0.0f);
      if (x + 1 < n && y + 1 < n) {
        const uint32_t i = uint32_t(y * n + x), m = uint32_t(n);
        grid.indices.insert(grid.indices.end(), {i, i + 1, i + m + 1, i, i + m + 1, i + m});
      }
    }
  grid.material = s.meshes.front().material;
  grid.skinning.skin = int(s.skins.size());
  grid.skinning.positions = grid.positions;
  grid.skinning.normals = grid.normals;
  SceneNode root, tip;
  tip.parent = int(s.nodes.size());
  s.nodes.push_back(root);
  s.nodes.push_back(tip);
  Skin skin;
  skin.joints = {tip.parent, tip.parent + 1};
  skin.inverseBind = {glm::dmat4(1.0), glm::dmat4(1.0)};
  s.skins.push_back(skin);
  Instance inst;
  inst.mesh = int(s.meshes.size());
  s.meshes.push_back(std::move(grid));
  s.instances.push_back(inst);
  AnimationChannel c;
  c.node = tip.parent + 1;
  c.path = AnimationPath::Rotation;
  const float h = float(M_PI) / 12.0f;  // half of 30 degrees
  c.times = {0.0f, 1.0f, 2.0f};
  c.values = {{0, 0, -std::sin(h), std::cos(h)},
              {0, 0, std::sin(h), std::cos(h)},
              {0, 0, -std::sin(h), std::cos(h)}};
  Animation swing;
  swing.name = "swing";
  swing.channels.push_back(c);
  s.animations.push_back(swing);
}

struct Timing {
  double frameMs = 0.0, animateMs = 0.0;
};

Timing measure(Scene& scene, bool animated, int w, int h, int frames, gl::Context& gl) {
  PipelineConfig config;
  config.layout = StereoLayout::dk2(w, h);
  FramePipeline pipeline(scene, config, &gl);
  if (animated) pipeline.animate(scene);
  StereoRig rig;
  rig.head = poseOf(scene.cameras.at(0));
  Timing t;
  for (int f = 0; f <= frames; ++f) {  // frame 0: the warm-up
    FrameRequest r;
    r.eyes = {rig.eye(Eye::Left, w, h, {}), rig.eye(Eye::Right, w, h, {})};
    r.index = uint32_t(f);
    r.sceneTime = animated ? f * kAnimationFrameSeconds : std::nan("");
    const auto t0 = Clock::now();
    StereoFrame frame = pipeline.render(r);
    const double ms = msSince(t0);
    if (f > 0) t.frameMs += ms / frames, t.animateMs += frame.times.animateMs / frames;
    pipeline.recycle(std::move(frame));
  }
  return t;
}

size_t skinnedVertices(const Scene& s) {
  size_t n = 0;
  for (const Mesh& m : s.meshes) n += m.skinned() ? m.vertexCount() : 0;
  return n;
}

const char* const kUsage =
    "usage: photovr_bench_animation [--out DIR] [--width W] [--height H] [--frames N]\n"
    "                               [--grid G]\n"
    "An animated frame against a static one: each built-in scene with every instance\n"
    "turning, and Cornell with a skinned G x G grid (256); hybrid, both eyes at W x H\n"
    "(240x270), 1 spp, 8 bounces, mean of N (8) frames. Writes bench_animation.csv to --out\n"
    "(out/bench).\n";

int run(const Options& o) {
  const std::string out = o.text("--out", "out/bench");
  const int w = o.integer("--width", 240, 1, 4096), h = o.integer("--height", 270, 1, 4096);
  const int frames = o.integer("--frames", 8, 1, 10000), grid = o.integer("--grid", 256, 2, 4096);
  const std::unique_ptr<gl::Context> ctx = gl::Context::createHeadless();
  std::printf(
      "bench_animation: %dx%d x 2 eyes, hybrid 1 spp 8 bounces, mean of %d frames; GL: %s\n", w, h,
      frames, ctx->renderer().c_str());
  std::filesystem::create_directories(out);
  std::ofstream csv(out + "/bench_animation.csv");
  csv << "scene,instances_moving,skinned_vertices,static_frame_ms,animated_frame_ms,pose_update_"
         "ms\n";
  std::printf("%-16s %8s %9s %10s %12s %14s\n", "scene", "moving", "skinned", "static ms",
              "animated ms", "pose+update ms");
  const auto row = [&](const std::string& name, Scene scene, size_t moving) {
    const Timing still = measure(scene, false, w, h, frames, *ctx);
    const Timing played = measure(scene, true, w, h, frames, *ctx);
    std::printf("%-16s %8zu %9zu %10.1f %12.1f %14.2f\n", name.c_str(), moving,
                skinnedVertices(scene), still.frameMs, played.frameMs, played.animateMs);
    csv << name << ',' << moving << ',' << skinnedVertices(scene) << ',' << still.frameMs << ','
        << played.frameMs << ',' << played.animateMs << '\n';
  };
  for (const std::string& name : builtinSceneNames()) {
    Scene scene = makeBuiltinScene(name);
    turnEveryInstance(scene);
    row(name, scene, scene.instances.size());
  }
  Scene skinned = makeBuiltinScene("cornell");
  addSkinnedGrid(skinned, grid);
  skinRestPose(skinned);
  row("cornell+skinned", skinned, 1);
  std::printf("wrote %s/bench_animation.csv\n", out.c_str());
  return 0;
}

}  // namespace
}  // namespace photovr

int main(int argc, char** argv) {
  return photovr::benchMain(argc, argv, photovr::kUsage,
                            {"--out", "--width", "--height", "--frames", "--grid"}, {},
                            photovr::run);
}
