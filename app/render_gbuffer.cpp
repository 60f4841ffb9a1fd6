// photovr render --mode gbuffer: the stereo G-buffer, written per eye and as one mosaic.
#include <chrono>
#include <cstdio>
#include <iostream>

#include "app/gbuffer_output.h"
#include "gl/render_context.h"
#include "app/render_request.h"
#include "gl/draw_stats.h"
#include "gl/gbuffer.h"
#include "gl/scene_gpu.h"

namespace photovr::app {

int renderGBufferMode(const RenderRequest& r) {
  auto context = gl::createRenderContext(r.backend);
  const auto eyes = eyeCameras(r.view, r.width, r.height, 0, r.sampler);
  gl::SceneGpu gpu(r.scene);
  gl::GBufferPass pass(r.width, r.height);
  const std::array<glm::mat4, 2> previous = {eyes[0].unjitteredProjection() * eyes[0].view(),
                                             eyes[1].unjitteredProjection() * eyes[1].view()};
  gl::resetDrawStats();
  const auto t0 = std::chrono::steady_clock::now();
  pass.render(gpu, eyes, previous);
  const gl::GBufferImage left = pass.read(0);
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  const gl::GBufferImage right = r.view.stereo ? pass.read(1) : gl::GBufferImage{};

  std::vector<std::string> written = writeEyeFiles(left, r.outDir + "/" + eyeFolder(r.view, 0));
  if (r.view.stereo)
    for (const std::string& p : writeEyeFiles(right, r.outDir + "/right")) written.push_back(p);
  writeImage(r.outDir + "/gbuffer.png", gbufferMosaic(left, r.view.stereo ? &right : nullptr));
  written.push_back(r.outDir + "/gbuffer.png");

  std::printf("scene %s: %zu triangles, %s\n", r.sceneSpec.c_str(),
              r.scene.instancedTriangleCount(), r.view.description.c_str());
  std::printf("G-buffer %dx%d x %d eyes: %llu draw calls, %.1f ms (render + read-back)\n", r.width,
              r.height, r.view.stereo ? 2 : 1, (unsigned long long)gl::drawStats().drawCalls, ms);
  std::printf("wrote:\n");
  for (const std::string& p : written) std::printf("  %s\n", p.c_str());
  return 0;
}

}  // namespace photovr::app
