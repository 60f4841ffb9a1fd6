// The same scene gives the same G-buffer under OSMesa and EGL (where EGL comes up).
#include <gtest/gtest.h>

#include "core/builtin_scenes.h"
#include "core/camera.h"
#include "gl/context.h"
#include "gl/gbuffer.h"
#include "tests/gl/gl_test_util.h"

namespace photovr {
namespace {

std::array<gl::GBufferImage, 2> renderWith(gl::Context& ctx, const Scene& scene) {
  ctx.makeCurrent();
  StereoRig rig;
  rig.head = poseOf(scene.cameras.at(0));
  const std::array<EyeCamera, 2> eyes = {
      rig.eye(Eye::Left, 48, 54, samplePosition(SamplerKind::Sobol, 3)),
      rig.eye(Eye::Right, 48, 54, samplePosition(SamplerKind::Sobol, 3))};
  gl::SceneGpu gpu(scene);
  gl::GBufferPass pass(48, 54, gl::EyeRouting::Layered);
  const glm::mat4 vp0 = eyes[0].unjitteredProjection() * eyes[0].view();
  const glm::mat4 vp1 = eyes[1].unjitteredProjection() * eyes[1].view();
  pass.render(gpu, eyes, {vp0, vp1});
  return {pass.read(0), pass.read(1)};
}

TEST(BackendParity, OSMesaAndEGLRenderTheSameGBuffer) {
  std::unique_ptr<gl::Context> egl;
  try {
    egl = gl::Context::create({gl::Backend::EGL});
  } catch (const gl::ContextError& e) {
    // Not a skip: EGL is the default backend and scripts/setup.sh installs Mesa's.
    FAIL() << "EGL unavailable here: " << e.what();
  }
  const Scene scene = makeBuiltinScene("cornell");
  const auto a = renderWith(*egl, scene);
  const auto b = renderWith(testing::osmesaContext(), scene);
  for (int e = 0; e < 2; ++e) {
    size_t covered = 0;
    for (size_t i = 0; i < a[e].visibility.size(); ++i) {
      // Both run Mesa's llvmpipe here, so the results are bit-identical; on a GPU the EGL
      // side would differ in rasterization rounding and this test would compare coverage.
      ASSERT_EQ(a[e].visibility[i], b[e].visibility[i]) << "eye " << e << " pixel " << i;
      ASSERT_EQ(a[e].depth[i], b[e].depth[i]);
      ASSERT_EQ(a[e].normal[i], b[e].normal[i]);
      ASSERT_EQ(a[e].baseColor[i], b[e].baseColor[i]);
      covered += a[e].visibility[i].x != kNoHitInstance;
    }
    EXPECT_EQ(covered, a[e].visibility.size());  // inside the closed box
  }
}

}  // namespace
}  // namespace photovr
