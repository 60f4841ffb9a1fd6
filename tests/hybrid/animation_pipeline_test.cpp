// An animated scene played through the frame pipeline (issue 23): a frame whose sceneTime
// poses the scene must equal, bit for bit, a frame of a fresh pipeline built on the scene
// posed at that time by hand. Whatever the pipeline forgets to follow shows: the GL
// instance data or skinned vertices (hybrid), the Embree top level or a skinned mesh's BVH
// (both modes), the light set of a moving emitter.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/animation.h"
#include "core/builtin_scenes.h"
#include "core/gltf_loader.h"
#include "hybrid/frame_pipeline.h"
#include "tests/core/skinned_glb.h"
#include "tests/core/test_dir.h"
#include "tests/gl/gl_test_util.h"

namespace photovr {
namespace {

constexpr int kW = 24, kH = 27;

// Cornell's ceiling light and short block on animated nodes: each keeps its placement as a
// matrix parent and slides on a TRS child (0.1 m a second sideways, the light 0.2 m).
Scene animatedCornell() {
  Scene s = makeBuiltinScene("cornell");
  Animation slide;
  slide.name = "slide";
  for (size_t k = 0; k < s.instances.size(); ++k) {
    const bool light =
        s.materials[size_t(s.meshes[size_t(s.instances[k].mesh)].material)].isEmissive();
    if (!light && s.instances[k].node != "short-block") continue;
    AnimationChannel c;
    c.node = addAnimatableNode(s, int(k));
    c.times = {0.0f, 1.0f};
    c.values = {glm::vec4(0.0f), glm::vec4(light ? 0.2f : 0.1f, 0.0f, 0.0f, 0.0f)};
    slide.channels.push_back(c);
  }
  EXPECT_EQ(slide.channels.size(), 2u);
  s.animations.push_back(slide);
  return s;
}

Scene skinnedBar() {
  Scene s = loadGltf(testing::skinnedFile(testing::freshTestDir("photovr_animation_pipeline")));
  s.environment.type = Environment::Type::Constant;  // the file has no light
  s.environment.constant = glm::vec3(1.0f);
  Camera c;
  c.position = {1.0f, 0.5f, 2.5f};
  s.cameras.push_back(c);
  return s;
}

FrameRequest requestAt(const Scene& s, FrameMode mode, double sceneTime) {
  StereoRig rig;
  rig.head = poseOf(s.cameras.at(0));
  FrameRequest r;
  r.eyes = {rig.eye(Eye::Left, kW, kH, {}), rig.eye(Eye::Right, kW, kH, {})};
  r.index = 5;
  r.settings.mode = mode;
  r.settings.spp = 2;
  r.settings.bounces = 3;
  r.settings.seed = 11;
  r.sceneTime = sceneTime;
  return r;
}

PipelineConfig configOf() {
  PipelineConfig c;
  c.layout = StereoLayout::dk2(kW, kH);
  return c;
}

// Frames at 0.2 s, then 0.7 s, played by one pipeline against a pipeline built at 0.7 s.
void expectPlayedEqualsPosedByHand(Scene played, Scene posed, FrameMode mode, gl::Context* gl) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  FramePipeline player(played, configOf(), gl);
  player.animate(played);
  player.render(requestAt(played, mode, 0.2));
  const StereoFrame got = player.render(requestAt(played, mode, 0.7));
  EXPECT_GT(got.times.animateMs, 0.0);
  poseScene(posed, 0.7, 0.2);
  FramePipeline fresh(posed, configOf(), gl);
  const StereoFrame expected = fresh.render(requestAt(posed, mode, kNaN));
  for (int e = 0; e < 2; ++e) {
    EXPECT_EQ(got.images[e].color, expected.images[e].color) << "eye " << e;
    EXPECT_EQ(got.images[e].depth, expected.images[e].depth) << "eye " << e;
  }
}

TEST(AnimationPipeline, PathTracedCornellWithAMovingLightAndBlock) {
  expectPlayedEqualsPosedByHand(animatedCornell(), animatedCornell(), FrameMode::PathTraced,
                                nullptr);
}

TEST(AnimationPipeline, HybridCornellWithAMovingLightAndBlock) {
  expectPlayedEqualsPosedByHand(animatedCornell(), animatedCornell(), FrameMode::Hybrid,
                                &testing::osmesaContext());
}

// pt: the primary rays find the bar in Embree (its refit BVH), not in the G-buffer.
TEST(AnimationPipeline, PathTracedSkinnedBar) {
  expectPlayedEqualsPosedByHand(skinnedBar(), skinnedBar(), FrameMode::PathTraced, nullptr);
}

TEST(AnimationPipeline, HybridSkinnedBar) {
  expectPlayedEqualsPosedByHand(skinnedBar(), skinnedBar(), FrameMode::Hybrid,
                                &testing::osmesaContext());
}

// The light set is rebuilt when an emitter moves, and only then.
TEST(AnimationPipeline, OnlyAMovingEmitterMovesTheLights) {
  Scene s = animatedCornell();
  EXPECT_TRUE(poseScene(s, 0.5, 0.4).lightsMoved);
  EXPECT_FALSE(poseScene(s, 0.5, 0.4).lightsMoved);  // posed again where it stands
  std::vector<AnimationChannel>& channels = s.animations[0].channels;
  std::erase_if(channels, [](const AnimationChannel& c) { return c.values[1].x == 0.2f; });
  ASSERT_EQ(channels.size(), 1u);                    // the light's slide is gone
  EXPECT_TRUE(poseScene(s, 0.7, 0.5).lightsMoved);   // the light back at its rest
  EXPECT_FALSE(poseScene(s, 0.9, 0.7).lightsMoved);  // the block alone moves
}

// The posed frame must differ from the unposed one, or the tests above prove nothing.
TEST(AnimationPipeline, PosingChangesTheFrame) {
  Scene played = animatedCornell();
  FramePipeline player(played, configOf(), nullptr);
  const StereoFrame still = player.render(requestAt(played, FrameMode::PathTraced, std::nan("")));
  player.animate(played);
  const StereoFrame moved = player.render(requestAt(played, FrameMode::PathTraced, 0.7));
  EXPECT_NE(still.images[0].color, moved.images[0].color);
}

TEST(AnimationPipeline, PipelinedSchedulingRefusesAnAnimatedScene) {
  Scene played = animatedCornell();
  FramePipeline player(played, configOf(), &testing::osmesaContext());
  player.animate(played);
  const auto requests = [&](uint32_t) { return requestAt(played, FrameMode::Hybrid, 0.1); };
  EXPECT_THROW(player.renderSequence(
                   requests, 2, FramePipeline::Scheduling::Pipelined, [](StereoFrame&) {}, nullptr),
               std::logic_error);
}

}  // namespace
}  // namespace photovr
