// photovr render: the G-buffer of both eyes, written per eye and as one mosaic.
#include <chrono>
#include <cstdio>
#include <iostream>

#include "app/commands.h"
#include "app/gbuffer_output.h"
#include "app/options.h"
#include "app/view.h"
#include "core/error.h"
#include "gl/context.h"
#include "gl/draw_stats.h"
#include "gl/gbuffer.h"
#include "gl/scene_gpu.h"

namespace photovr::app {
namespace {

const char* const kRenderHelp =
    "usage: photovr render [options]\n"
    "Renders the stereo G-buffer of a scene headless and writes, per eye (left/, right/ or\n"
    "mono/), depth.exr (reversed-Z: near 1, far 0), normal.png, albedo.png, ids.png, and a\n"
    "gbuffer.png mosaic (albedo, normal / ids, depth; eyes side by side).\n"
    "  --scene NAME|FILE      atrium (default), cornell, spheres, or a .gltf/.glb file\n"
    "  --env FILE             equirectangular .hdr/.exr environment\n"
    "  --width W --height H   per-eye size (default 960x1080, the DK2's eye; 1..8192)\n"
    "  --backend B            egl (default, falls back to osmesa), osmesa, glfw\n"
    "  --out DIR              output folder (default out/<scene>)\n";

std::unique_ptr<gl::Context> createContext(const Options& o) {
  if (o.has("--backend")) return gl::Context::create({gl::parseBackend(o.text("--backend", ""))});
  try {
    return gl::Context::create({gl::Backend::EGL});
  } catch (const gl::ContextError& e) {
    std::cerr << "photovr: " << e.what() << "; using osmesa\n";
    return gl::Context::create({gl::Backend::OSMesa});
  }
}

std::string defaultOutDir(const std::string& scene) {
  const size_t slash = scene.find_last_of('/');
  std::string stem = scene.substr(slash == std::string::npos ? 0 : slash + 1);
  stem = stem.substr(0, stem.find_last_of('.'));
  return "out/" + (stem.empty() ? std::string("scene") : stem);
}

double millisecondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int runRender(const Args& args) {
  if (wantsHelp(args)) {
    std::cout << kRenderHelp << kViewHelp;
    return 0;
  }
  std::set<std::string> valued = {"--scene", "--env", "--width", "--height", "--backend", "--out"};
  valued.insert(kViewOptions.begin(), kViewOptions.end());
  const Options o(args, valued, {});
  if (!o.positional().empty()) throw UsageError("render: unexpected argument '" + o.positional()[0] + "'");
  const std::string sceneSpec = o.text("--scene", "atrium");
  const int width = o.integer("--width", kDk2EyeWidth, 1, 8192);
  const int height = o.integer("--height", kDk2EyeHeight, 1, 8192);
  const std::string outDir = o.text("--out", defaultOutDir(sceneSpec));
  Scene scene = loadSceneSpec(sceneSpec);
  applyEnvironmentOption(scene, o.text("--env", ""));
  const View view = resolveView(scene, o);
  auto context = createContext(o);
  std::cerr << "photovr: " << gl::backendName(context->backend()) << ", OpenGL "
            << context->version() << ", " << context->renderer() << "\n";

  const auto eyes = eyeCameras(view, width, height, 0);
  gl::SceneGpu gpu(scene);
  gl::GBufferPass pass(width, height, context->hasExtension("GL_ARB_shader_viewport_layer_array"),
                       gl::EyeRouting::Layered);
  const std::array<glm::mat4, 2> previous = {eyes[0].unjitteredProjection() * eyes[0].view(),
                                             eyes[1].unjitteredProjection() * eyes[1].view()};
  gl::resetDrawStats();
  const auto t0 = std::chrono::steady_clock::now();
  pass.render(gpu, eyes, previous);
  const gl::GBufferImage left = pass.read(0);
  const double ms = millisecondsSince(t0);
  const gl::GBufferImage right = view.stereo ? pass.read(1) : gl::GBufferImage{};

  std::vector<std::string> written =
      writeEyeFiles(left, outDir + (view.stereo ? "/left" : "/mono"));
  if (view.stereo)
    for (const std::string& p : writeEyeFiles(right, outDir + "/right")) written.push_back(p);
  writeImage(outDir + "/gbuffer.png", gbufferMosaic(left, view.stereo ? &right : nullptr));
  written.push_back(outDir + "/gbuffer.png");

  const gl::DrawStats& s = gl::drawStats();
  std::printf("scene %s: %zu triangles, %s\n", sceneSpec.c_str(), scene.instancedTriangleCount(),
              view.description.c_str());
  std::printf("G-buffer %dx%d x %d eyes: %llu draw calls, %.1f ms (render + read-back)\n", width,
              height, view.stereo ? 2 : 1, (unsigned long long)s.drawCalls, ms);
  std::printf("wrote:\n");
  for (const std::string& p : written) std::printf("  %s\n", p.c_str());
  return 0;
}

}  // namespace photovr::app
