#include "core/view.h"

#include <cmath>

#include "core/error.h"

namespace photovr {

const char* const kHeadHelp =
    "  --camera N|NAME        scene camera by index or name (default: the first, else a\n"
    "                         view framing the scene)\n"
    "  --look-from X,Y,Z      camera position (overrides the scene camera's)\n"
    "  --look-at X,Y,Z        point to look at (overrides the orientation)\n"
    "  --time T               scene time in seconds: animated glTF files are posed there,\n"
    "                         each animation looping over its own length (default 0)\n";

const char* const kEyesHelp =
    "  --fovy DEG             vertical field of view for --eyes mono (1..179)\n"
    "  --eyes stereo|mono     stereo: both eyes around the camera, 63.5 mm IPD, DK2 FOV\n"
    "                         (default); mono: the camera's own symmetric frustum\n";

const std::set<std::string> kViewOptions = {"--camera", "--look-from", "--look-at",
                                            "--fovy",   "--eyes",      "--time"};

namespace {

constexpr float kDegrees = float(M_PI) / 180.0f;

int findCamera(const Scene& scene, const std::string& spec) {
  for (size_t i = 0; i < scene.cameras.size(); ++i)
    if (scene.cameras[i].name == spec) return int(i);
  char* end = nullptr;
  const long index = std::strtol(spec.c_str(), &end, 10);
  if (!spec.empty() && *end == '\0' && index >= 0 && size_t(index) < scene.cameras.size())
    return int(index);
  std::string names;
  for (size_t i = 0; i < scene.cameras.size(); ++i)
    names += (i ? ", " : "") + std::to_string(i) + " '" + scene.cameras[i].name + "'";
  throw UsageError("--camera: '" + spec + "' is not a camera of this scene (" +
                   (names.empty() ? "it has none" : names) + ")");
}

// A view of the whole scene from its +Z side, for files without cameras.
View framingView(const Scene& scene) {
  const Bounds b = scene.worldBounds();
  const float radius = std::max(0.5f * glm::length(b.extent()), 1e-3f);
  View v;
  v.yfov = 50.0f * kDegrees;
  const float distance = radius / std::tan(0.5f * v.yfov);
  v.head = lookAt(b.center() + glm::vec3(0.0f, 0.25f * radius, distance), b.center());
  v.description = "framing the scene bounds (no camera in the scene)";
  return v;
}

}  // namespace

View resolveView(const Scene& scene, const Options& o) {
  View v;
  if (o.has("--camera") || !scene.cameras.empty()) {
    const int index = findCamera(scene, o.text("--camera", "0"));
    const Camera& c = scene.cameras[index];
    v.head = poseOf(c);
    v.yfov = c.yfov;
    v.description = "camera " + std::to_string(index) + " '" + c.name + "'";
  } else {
    v = framingView(scene);
  }
  if (auto from = o.vec3("--look-from")) {
    v.head.position = *from;
    v.description += ", moved to --look-from";
  }
  if (auto at = o.vec3("--look-at")) {
    if (glm::length(*at - v.head.position) < 1e-6f)
      throw UsageError("--look-at: the target coincides with the camera position");
    v.head = lookAt(v.head.position, *at);
    v.description += ", aimed with --look-at";
  }
  v.yfov = o.number("--fovy", v.yfov / kDegrees, 1.0f, 179.0f) * kDegrees;
  v.stereo = o.choice("--eyes", "stereo", {"stereo", "mono"}) == "stereo";
  if (v.stereo && o.has("--fovy"))
    throw UsageError("--fovy: only with --eyes mono (the stereo eyes have the DK2's FOV)");
  return v;
}

std::array<EyeCamera, 2> eyeCameras(const View& view, int width, int height, uint32_t frame,
                                    SamplerKind sampler) {
  const glm::vec2 jitter = samplePosition(sampler, frame);
  if (view.stereo) {
    StereoRig rig;
    rig.head = view.head;
    return {rig.eye(Eye::Left, width, height, jitter), rig.eye(Eye::Right, width, height, jitter)};
  }
  EyeCamera c;
  c.pose = view.head;
  c.fov = FovTangents::symmetric(view.yfov, float(width) / float(height));
  c.width = width;
  c.height = height;
  c.jitter = jitter;
  return {c, c};
}

}  // namespace photovr
