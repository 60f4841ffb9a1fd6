// glTF animations (glTF 2.0 §3.11, interpolation as its Appendix C): node translation,
// rotation and scale channels, sampled at a scene time, and the scene posed there.
//
// The loader keeps the file's node hierarchy (SceneNode) when the file animates it; posing
// recomposes every node's world transform in double, re-based at Scene::origin, and writes
// the instances', lights' and cameras' float transforms, with the previous time's pose in
// Instance::previousTransform for the G-buffer's motion vectors.
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace photovr {

struct Scene;

// One node of the file's hierarchy, parents stored before their children.
struct SceneNode {
  std::string name;
  int parent = -1;  // index into Scene::nodes
  // The rest pose: a matrix node is never animated (glTF 2.0 §3.11: "When a node is
  // targeted for animation, only TRS properties may be present").
  bool hasMatrix = false;
  glm::dmat4 matrix{1.0};
  glm::dvec3 translation{0.0};
  glm::dquat rotation{1.0, 0.0, 0.0, 0.0};
  glm::dvec3 scale{1.0};
  std::vector<int> instances, lights, cameras;  // what the node carries (Scene indices)
};

// glTF 2.0 §3.7.3: a skeleton. Each joint's skinning matrix is its world transform times
// its inverse bind matrix.
struct Skin {
  std::string name;
  std::vector<int> joints;              // indices into Scene::nodes
  std::vector<glm::dmat4> inverseBind;  // per joint; identity where the file gives none
};

enum class AnimationPath { Translation, Rotation, Scale };
enum class Interpolation { Step, Linear, CubicSpline };

struct AnimationChannel {
  int node = -1;  // index into Scene::nodes
  AnimationPath path = AnimationPath::Translation;
  Interpolation interpolation = Interpolation::Linear;
  std::vector<float> times;       // seconds, strictly increasing
  std::vector<glm::vec4> values;  // xyz (translation, scale) or xyzw (rotation); cubic
                                  // splines hold in-tangent, value, out-tangent per key
};

struct Animation {
  std::string name;
  std::vector<AnimationChannel> channels;
  float duration() const;  // the last key time of any channel
};

// The channel's value at time t (seconds), as Appendix C defines it: held at the first and
// last keys outside their range; rotations slerped (linear) or normalised (cubic).
glm::dvec4 sampleChannel(const AnimationChannel& channel, double t);

// The scene clock's step when nothing else sets it: one frame of the DK2's 75 Hz panel.
constexpr double kAnimationFrameSeconds = 1.0 / 75.0;

// Whether the scene moves: it has an animation with at least one channel.
bool isAnimated(const Scene& scene);

// What a pose changed, for the renderers to update no more than that.
struct SceneMotion {
  bool lightsMoved = false;         // a punctual light or an emissive instance moved
  std::vector<int> deformedMeshes;  // skinned meshes whose vertices were rewritten
};

// Poses the scene at time t (every animation playing at once, each looping over its own
// duration), with the pose at 'previousT' as every instance's previous transform; skinned
// meshes are deformed to the pose at t (core/skinning.h).
SceneMotion poseScene(Scene& scene, double t, double previousT);

// For scenes made in code (built-in ones have no hierarchy): puts the instance on a new TRS
// node, child of a matrix node holding its placement, and returns the TRS node's index, for
// channels to animate in the instance's own frame.
int addAnimatableNode(Scene& scene, int instance);

// Deforms every skinned mesh to the node hierarchy's rest pose (no animation applied): the
// loader's last step, since a skinned mesh's bind pose is not its rest pose.
void skinRestPose(Scene& scene);

}  // namespace photovr
