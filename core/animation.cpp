#include "core/animation.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "core/scene.h"
#include "core/skinning.h"

namespace photovr {
namespace {

glm::dquat asQuat(const glm::dvec4& v) {
  return glm::dquat(v.w, v.x, v.y, v.z);  // glTF stores (x, y, z, w); glm takes w first
}

glm::dvec4 asVec(const glm::dquat& q) {
  return glm::dvec4(q.x, q.y, q.z, q.w);
}

glm::dvec4 normalizedRotation(const glm::dvec4& v) {
  const double length = glm::length(v);
  return length > 0.0 ? v / length : glm::dvec4(0.0, 0.0, 0.0, 1.0);
}

// Key k's value: the middle of the three a cubic spline stores per key.
glm::dvec4 keyValue(const AnimationChannel& c, size_t k) {
  return glm::dvec4(c.values[c.interpolation == Interpolation::CubicSpline ? 3 * k + 1 : k]);
}

// Appendix C, cubic spline: Hermite between keys k and k+1 with the out-tangent of k and
// the in-tangent of k+1, both scaled by the key interval td.
glm::dvec4 hermite(const AnimationChannel& c, size_t k, double s, double td) {
  const double s2 = s * s, s3 = s2 * s;
  const glm::dvec4 v0(c.values[3 * k + 1]), b0(c.values[3 * k + 2]);
  const glm::dvec4 a1(c.values[3 * k + 3]), v1(c.values[3 * k + 4]);
  return (2 * s3 - 3 * s2 + 1) * v0 + td * (s3 - 2 * s2 + s) * b0 + (-2 * s3 + 3 * s2) * v1 +
         td * (s3 - s2) * a1;
}

}  // namespace

float Animation::duration() const {
  float d = 0.0f;
  for (const AnimationChannel& c : channels)
    if (!c.times.empty()) d = std::max(d, c.times.back());
  return d;
}

glm::dvec4 sampleChannel(const AnimationChannel& c, double t) {
  const size_t keys = c.times.size();
  if (keys == 0) return glm::dvec4(0.0);
  if (!(t > double(c.times.front())) || keys == 1) return keyValue(c, 0);
  if (t >= double(c.times.back())) return keyValue(c, keys - 1);
  // The key interval [t_k, t_k+1) that holds t.
  const size_t k =
      size_t(std::upper_bound(c.times.begin(), c.times.end(), float(t)) - c.times.begin()) - 1;
  const double t0 = c.times[k], td = double(c.times[k + 1]) - t0;
  const double s = std::clamp((t - t0) / td, 0.0, 1.0);
  const bool rotation = c.path == AnimationPath::Rotation;
  switch (c.interpolation) {
    case Interpolation::Step:
      return keyValue(c, k);
    case Interpolation::CubicSpline: {
      const glm::dvec4 v = hermite(c, k, s, td);
      return rotation ? normalizedRotation(v) : v;
    }
    case Interpolation::Linear:
      break;
  }
  if (rotation) return asVec(glm::slerp(asQuat(keyValue(c, k)), asQuat(keyValue(c, k + 1)), s));
  return glm::mix(keyValue(c, k), keyValue(c, k + 1), s);
}

bool isAnimated(const Scene& scene) {
  for (const Animation& a : scene.animations)
    if (!a.channels.empty()) return true;
  return false;
}

namespace {

// Every node's local TRS at time t: the rest pose with each animation's channels applied
// (none when t is NaN: the rest pose itself).
std::vector<SceneNode> localPoses(const Scene& scene, double t) {
  std::vector<SceneNode> nodes = scene.nodes;
  if (std::isnan(t)) return nodes;
  for (const Animation& a : scene.animations) {
    const double duration = double(a.duration());
    const double local = duration > 0.0 ? t - duration * std::floor(t / duration) : 0.0;
    for (const AnimationChannel& c : a.channels) {
      if (c.node < 0 || size_t(c.node) >= nodes.size()) continue;
      SceneNode& n = nodes[size_t(c.node)];
      const glm::dvec4 v = sampleChannel(c, local);
      if (c.path == AnimationPath::Translation) n.translation = glm::dvec3(v);
      if (c.path == AnimationPath::Rotation) n.rotation = asQuat(normalizedRotation(v));
      if (c.path == AnimationPath::Scale) n.scale = glm::dvec3(v);
    }
  }
  return nodes;
}

glm::dmat4 localMatrix(const SceneNode& n) {
  if (n.hasMatrix) return n.matrix;
  return glm::translate(glm::dmat4(1.0), n.translation) * glm::mat4_cast(n.rotation) *
         glm::scale(glm::dmat4(1.0), n.scale);
}

// World transforms in the scene's coordinates: the file's, re-based at Scene::origin.
std::vector<glm::dmat4> worldPoses(const Scene& scene, double t) {
  const std::vector<SceneNode> nodes = localPoses(scene, t);
  const glm::dmat4 toScene = glm::translate(glm::dmat4(1.0), -scene.origin);
  std::vector<glm::dmat4> world(nodes.size());
  for (size_t i = 0; i < nodes.size(); ++i) {
    const int p = nodes[i].parent;
    const glm::dmat4& parent = p >= 0 && size_t(p) < i ? world[size_t(p)] : toScene;
    world[i] = parent * localMatrix(nodes[i]);
  }
  return world;
}

glm::quat rotationOf(const glm::dmat4& world) {
  glm::dmat3 r(world);
  for (int c = 0; c < 3; ++c) r[c] = glm::normalize(r[c]);  // drop the node's scale
  return glm::quat(glm::normalize(glm::quat_cast(r)));
}

// The joints' world transforms at t and at the previous time (null: the rest pose, no
// motion). When the mesh was last posed at exactly that previous time (a played sequence)
// its positions are kept as the previous ones instead of being skinned again: the same
// floats, as skinPositions and skinMesh compute a position by the same expression.
struct JointPoses {
  const std::vector<glm::dmat4>& now;
  const std::vector<glm::dmat4>* before;
  double t, previousT;
};

// Skinned meshes follow their joints: their instances stay at identity (glTF 2.0 §3.7.3.3:
// the skinned mesh node's own transform is ignored), the vertices move.
void skinAll(Scene& scene, const JointPoses& poses, SceneMotion& motion) {
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    Mesh& mesh = scene.meshes[m];
    if (!mesh.skinned() || size_t(mesh.skinning.skin) >= scene.skins.size()) continue;
    const Skin& skin = scene.skins[size_t(mesh.skinning.skin)];
    MeshSkinning& s = mesh.skinning;
    if (poses.before && s.posedAt == poses.previousT)
      s.previousPositions = mesh.positions;
    else if (poses.before)
      skinPositions(s, skinningMatrices(skin, *poses.before), s.previousPositions);
    skinMesh(mesh, skinningMatrices(skin, poses.now));
    if (!poses.before) s.previousPositions = mesh.positions;
    s.posedAt = poses.t;
    motion.deformedMeshes.push_back(int(m));
    motion.lightsMoved |= scene.materials[size_t(mesh.material)].isEmissive();
  }
}

}  // namespace

SceneMotion poseScene(Scene& scene, double t, double previousT) {
  const std::vector<glm::dmat4> now = worldPoses(scene, t);
  const std::vector<glm::dmat4> before = worldPoses(scene, previousT);
  SceneMotion motion;
  for (size_t i = 0; i < scene.nodes.size(); ++i) {
    const SceneNode& n = scene.nodes[i];
    for (int k : n.instances) {
      Instance& inst = scene.instances[size_t(k)];
      if (scene.hasMesh(inst.mesh) && scene.meshes[size_t(inst.mesh)].skinned()) {
        // Its vertices are written in scene coordinates below; a re-base since the last
        // pose (core/scene_transform.h) may have moved the instance.
        inst.transform = inst.previousTransform = glm::mat4(1.0f);
        continue;
      }
      const glm::mat4 pose(now[i]);
      // Only an emitter that moved makes the light set rebuild (static ones under an
      // animated file's nodes are posed too).
      if (scene.hasMesh(inst.mesh) && pose != inst.transform)
        motion.lightsMoved |=
            scene.materials[size_t(scene.meshes[size_t(inst.mesh)].material)].isEmissive();
      inst.transform = pose;
      inst.previousTransform = glm::mat4(before[i]);
    }
    for (int k : n.lights) {
      Light& l = scene.lights[size_t(k)];
      const glm::vec3 position(now[i][3]);
      const glm::vec3 direction(glm::normalize(glm::dmat3(now[i]) * glm::dvec3(0, 0, -1)));
      motion.lightsMoved |= position != l.position || direction != l.direction;
      l.position = position;
      l.direction = direction;
    }
    for (int k : n.cameras) {
      scene.cameras[size_t(k)].position = glm::vec3(now[i][3]);
      scene.cameras[size_t(k)].orientation = rotationOf(now[i]);
    }
  }
  skinAll(scene, {now, &before, t, previousT}, motion);
  return motion;
}

int addAnimatableNode(Scene& scene, int instance) {
  const Instance& inst = scene.instances[size_t(instance)];
  SceneNode placement, child;
  placement.name = inst.node + " placement";
  placement.hasMatrix = true;
  placement.matrix = glm::dmat4(inst.transform);
  child.name = inst.node;
  child.parent = int(scene.nodes.size());
  child.instances = {instance};
  scene.nodes.push_back(placement);
  scene.nodes.push_back(child);
  return child.parent + 1;
}

void skinRestPose(Scene& scene) {
  SceneMotion ignored;
  const double rest = std::nan("");
  skinAll(scene, {worldPoses(scene, rest), nullptr, rest, rest}, ignored);
}

}  // namespace photovr
