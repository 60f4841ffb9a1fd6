// The frame pipeline (hybrid/frame_pipeline.h) adds ownership and scheduling, never pixels:
// each of its frames is bit-identical to what the parts it wires give when called by hand
// (HybridRenderer, renderPathTraced, the denoiser), whatever the scheduling; the denoiser's
// history follows the documented rules; pt without the denoiser needs no GL.
#include <gtest/gtest.h>

#include <array>
#include <stdexcept>
#include <utility>

#include "core/builtin_scenes.h"
#include "hybrid/denoise_input.h"
#include "hybrid/frame_pipeline.h"
#include "hybrid/hybrid_renderer.h"
#include "tests/gl/gl_test_util.h"
#include "trace/embree_scene.h"
#include "trace/lights.h"

namespace photovr {
namespace {

constexpr int kW = 24, kH = 27;

std::array<EyeCamera, 2> eyesOf(const Scene& s, uint32_t frame) {
  StereoRig rig;
  rig.head = poseOf(s.cameras.at(0));
  const glm::vec2 jitter = samplePosition(SamplerKind::Sobol, frame);
  return {rig.eye(Eye::Left, kW, kH, jitter), rig.eye(Eye::Right, kW, kH, jitter)};
}

PipelineConfig configOf() {
  PipelineConfig c;
  c.layout = StereoLayout::dk2(kW, kH);
  return c;
}

FrameRequest requestOf(const Scene& s, uint32_t frame, FrameMode mode,
                       gl::DenoiseMode denoise = gl::DenoiseMode::Off) {
  FrameRequest r{eyesOf(s, frame), 2, frame, {}};
  r.settings.mode = mode;
  r.settings.spp = 2;
  r.settings.bounces = 3;
  r.settings.seed = 7;
  r.settings.denoise = denoise;
  return r;
}

TEST(FramePipeline, HybridFramesEqualTheHybridRenderersAndTheWorkersEqualBoth) {
  const Scene scene = makeBuiltinScene("cornell");
  gl::Context& ctx = testing::osmesaContext();
  const FrameRequest q = requestOf(scene, 3, FrameMode::Hybrid);
  HybridRenderer direct(scene, kW, kH, traceSettingsOf(q.settings));
  const auto expected = direct.render(q.eyes, 2, q.index, nullptr);
  FramePipeline sequential(scene, configOf(), &ctx);
  const StereoFrame got = sequential.render(q);
  FramePipeline background(scene, configOf(), &ctx);
  background.start(q);
  std::optional<StereoFrame> worker;
  while (!(worker = background.take())) {
  }
  for (int e = 0; e < 2; ++e) {
    EXPECT_EQ(got.images[e].color, expected[e].color) << "eye " << e;
    EXPECT_EQ(got.images[e].diffuse, expected[e].diffuse) << "eye " << e;
    EXPECT_EQ(worker->images[e].color, expected[e].color) << "eye " << e;
    EXPECT_EQ(worker->images[e].samples, expected[e].samples) << "eye " << e;
  }
  EXPECT_EQ(got.times.rays, expected[0].rays + expected[1].rays);
  EXPECT_FALSE(got.denoised);
}

TEST(FramePipeline, PathTracedFramesNeedNoGlAndEqualRenderPathTraced) {
  const Scene scene = makeBuiltinScene("spheres");
  FramePipeline pipeline(scene, configOf(), nullptr);
  const FrameRequest q = requestOf(scene, 1, FrameMode::PathTraced);
  StereoFrame first = pipeline.render(q);
  pipeline.recycle(std::move(first));  // the next frame is traced into its storage
  const StereoFrame got = pipeline.render(q);
  const EmbreeScene embree(scene);
  const LightSet lights(scene);
  const TraceContext tc{scene, embree, lights, traceSettingsOf(q.settings)};
  StereoPaths stereo;  // the pipeline's stereo reuse, as it runs it
  const StereoTurns turns = stereoTurnsOf(q.settings.stereoReuse, 2, q.index, stereo, q.eyes[0],
                                          uint32_t(tc.settings.samplesPerPixel));
  for (int turn = 0; turn < 2; ++turn) {
    const int e = turns.order[turn];
    const EyeImage want = renderPathTraced(tc, q.eyes[e], uint32_t(e), q.index, {}, turns.roles[e]);
    EXPECT_EQ(got.images[e].color, want.color) << "eye " << e;
    EXPECT_EQ(got.images[e].samples, want.samples) << "eye " << e;
    EXPECT_GT(got.times.turnTraceMs[turn], 0.0);
  }
  // A frame that needs GL says so instead of crashing.
  EXPECT_THROW(pipeline.render(requestOf(scene, 0, FrameMode::Hybrid)), std::logic_error);
}

TEST(FramePipeline, DenoisedFramesEqualTheDenoiserRunByHandAndSwitchingModeResetsHistory) {
  const Scene scene = makeBuiltinScene("cornell");
  gl::Context& ctx = testing::osmesaContext();
  FramePipeline pipeline(scene, configOf(), &ctx);
  // By hand: the renderer, its G-buffer as guides, history reset on frame 0 only.
  const FrameRequest q0 = requestOf(scene, 0, FrameMode::Hybrid, gl::DenoiseMode::Full);
  const FrameRequest q1 = requestOf(scene, 1, FrameMode::Hybrid, gl::DenoiseMode::Full);
  HybridRenderer direct(scene, kW, kH, traceSettingsOf(q0.settings));
  gl::Denoiser denoiser(kW, kH);
  for (const FrameRequest* q : {&q0, &q1}) {
    const auto img = direct.render(q->eyes, 2, q->index, nullptr);
    const DenoiseInput l = makeDenoiseInput(img[0]), r = makeDenoiseInput(img[1]);
    denoiser.run(direct.gbuffer(), {l.eye, r.eye}, 2, gl::DenoiseMode::Full, q->index == 0);
  }
  for (const FrameRequest* q : {&q0, &q1}) {
    StereoFrame f = pipeline.render(*q);
    EXPECT_TRUE(f.denoised);
    pipeline.recycle(std::move(f));
  }
  for (int e = 0; e < 2; ++e)
    EXPECT_EQ(pipeline.denoiser()->readLinear(e), denoiser.readLinear(e)) << "eye " << e;
  // A pt frame after hybrid ones starts a new history: equal to a pt frame denoised first.
  const FrameRequest p = requestOf(scene, 2, FrameMode::PathTraced, gl::DenoiseMode::Full);
  pipeline.recycle(pipeline.render(p));
  FramePipeline fresh(scene, configOf(), &ctx);
  fresh.recycle(fresh.render(p));
  for (int e = 0; e < 2; ++e)
    EXPECT_EQ(pipeline.denoiser()->readLinear(e), fresh.denoiser()->readLinear(e)) << "eye " << e;
}

TEST(FramePipeline, PipelinedSequencesEqualSequentialOnesAndRefuseTheDenoiser) {
  const Scene scene = makeBuiltinScene("cornell");
  gl::Context& ctx = testing::osmesaContext();
  FramePipeline pipeline(scene, configOf(), &ctx);
  std::array<std::array<std::vector<glm::vec3>, 2>, 2> colors;  // [scheduling][frame 1 eye]
  for (int s = 0; s < 2; ++s) {
    const auto scheduling =
        s ? FramePipeline::Scheduling::Pipelined : FramePipeline::Scheduling::Sequential;
    pipeline.renderSequence([&](uint32_t f) { return requestOf(scene, f, FrameMode::Hybrid); }, 3,
                            scheduling,
                            [&](StereoFrame& f) {
                              if (f.request.index == 1)
                                colors[s] = {f.images[0].color, f.images[1].color};
                            },
                            nullptr);
  }
  EXPECT_EQ(colors[0], colors[1]);
  EXPECT_THROW(
      pipeline.renderSequence(
          [&](uint32_t f) { return requestOf(scene, f, FrameMode::Hybrid, gl::DenoiseMode::Full); },
          2, FramePipeline::Scheduling::Pipelined, [](StereoFrame&) {}, nullptr),
      std::logic_error);
}

TEST(FramePipeline, SampleMapsAreTheLenssCachedPerKindAndSpp) {
  const Scene scene = makeBuiltinScene("cornell");
  gl::Context& ctx = testing::osmesaContext();
  FramePipeline pipeline(scene, configOf(), &ctx);
  const StereoSampleMaps& a = pipeline.sampleMaps(SampleMapKind::HiddenArea, 3);
  EXPECT_EQ(&a, &pipeline.sampleMaps(SampleMapKind::HiddenArea, 3));
  const StereoSampleMaps want = lensSampleMaps(SampleMapKind::HiddenArea, configOf().layout, 3);
  for (int e = 0; e < 2; ++e) EXPECT_EQ(a[e].perPixel(), want[e].perPixel());
  EXPECT_TRUE(pipeline.sampleMaps(SampleMapKind::Uniform, 3)[0].isUniform());
  // A hidden-area frame traces no sample where the map says 0.
  FrameRequest q = requestOf(scene, 0, FrameMode::Hybrid);
  q.settings.spp = 3;
  q.settings.sampleMap = SampleMapKind::HiddenArea;
  const StereoFrame f = pipeline.render(q);
  size_t hidden = 0;
  for (int e = 0; e < 2; ++e)
    for (size_t i = 0; i < f.images[e].samples.size(); ++i)
      if (a[e].skips(i)) {
        EXPECT_EQ(f.images[e].samples[i], 0u);
        ++hidden;
      }
  EXPECT_GT(hidden, 0u);  // the DK2 lens hides the buffer's corners
}

}  // namespace
}  // namespace photovr
