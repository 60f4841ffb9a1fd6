// Stereo camera math shared by the rasterizer and the ray tracer, so that both see the
// same rays: eye poses from a head pose and an IPD, asymmetric per-eye frusta from FOV
// tangents, reversed-Z projection and the per-frame sub-pixel jitter.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "core/scene.h"

namespace photovr {

// Rigid pose: camera-to-world, looking down -Z with +Y up.
struct Pose {
  glm::vec3 position{0.0f};
  glm::quat orientation{1.0f, 0.0f, 0.0f, 0.0f};
  glm::mat4 toWorld() const;
  glm::mat4 fromWorld() const;  // the view matrix
};

// Tangents of the half-angles from the view axis to each frustum edge (all positive).
struct FovTangents {
  float left = 1.0f, right = 1.0f, up = 1.0f, down = 1.0f;
  // The DK2's left eye (../shared/reference/dk2.md §5, LibOVR 0.4 defaults at 11 mm eye
  // relief): outer (left) 1.0587, nasal (right) 1.0924, up and down 1.3293.
  static FovTangents dk2LeftEye() { return {1.0587f, 1.0924f, 1.3293f, 1.3293f}; }
  static FovTangents symmetric(float yfov, float aspect);
  FovTangents mirrored() const { return {right, left, up, down}; }  // left eye -> right eye
  // The smallest FOV holding every direction within 'radians' of this one (the bounding
  // box of the field grown by that angle). An edge moves out by more than the angle: the
  // farthest direction from it is that of a field corner turned about the edge's axis.
  FovTangents widened(float radians) const;
};

enum class Eye : int { Left = 0, Right = 1 };
constexpr float kDefaultIpd = 0.0635f;  // metres; DK2 lens separation (dk2.md §5)
// DK2 panel: 1920x1080 landscape, 960x1080 per eye (dk2.md §5).
constexpr int kDk2EyeWidth = 960;
constexpr int kDk2EyeHeight = 1080;

// The eye buffers of a headset frame: their size and FOV. Overscan renders them a margin
// beyond the lens's field on every side, at the field's pixels per tan-angle (the buffers
// grow), so that re-projecting to a head turned by up to the margin finds rendered pixels
// where it would otherwise show black (gl/timewarp.h). The panel still shows the field
// alone; the margin is not traced where the lens cannot reach it even after such a turn
// (hmd/lens_maps.h hiddenAreaMask).
struct StereoLayout {
  int width = kDk2EyeWidth, height = kDk2EyeHeight;   // pixels, overscan included
  FovTangents leftFov = FovTangents::dk2LeftEye();    // the buffer's; the right eye mirrors it
  FovTangents leftField = FovTangents::dk2LeftEye();  // the lens's field the panel shows
  float overscan = 0.0f;                              // radians beyond the field
  // A headset's field ('leftField', the right eye mirrored) at fieldWidth x fieldHeight,
  // widened by 'overscanRadians' per side (hmd/headset_description.h builds it).
  static StereoLayout forField(const FovTangents& leftField, int fieldWidth, int fieldHeight,
                               float overscanRadians = 0.0f);
  // The DK2's (forField of FovTangents::dk2LeftEye()), for tests and benches.
  static StereoLayout dk2(int fieldWidth, int fieldHeight, float overscanRadians = 0.0f) {
    return forField(FovTangents::dk2LeftEye(), fieldWidth, fieldHeight, overscanRadians);
  }
  FovTangents fov(Eye e) const { return e == Eye::Left ? leftFov : leftFov.mirrored(); }
  FovTangents field(Eye e) const { return e == Eye::Left ? leftField : leftField.mirrored(); }
};

// One eye's camera for one frame.
struct EyeCamera {
  Pose pose;
  FovTangents fov;
  float znear = 0.05f;
  float zfar = 0.0f;          // 0 = infinite reversed-Z
  glm::vec2 jitter{0.0f};     // sub-pixel offset of the sample from the pixel centre
  int width = 1, height = 1;  // image size in pixels

  // World-space ray through the sample of pixel (x, y), pixels counted from the LOWER-left
  // as GL's gl_FragCoord does; the sample sits at (x + 0.5, y + 0.5) + jitter.
  glm::vec3 rayDirection(float px, float py) const;  // px, py: window coordinates of the sample
  glm::vec3 pixelRay(int x, int y) const {
    return rayDirection(x + 0.5f + jitter.x, y + 0.5f + jitter.y);
  }
  // Linear map from window coordinates to the unnormalised world direction:
  // dir = base + px * dx + py * dy (used identically by the shaders).
  glm::vec3 rayBase() const;
  glm::vec3 rayDx() const;
  glm::vec3 rayDy() const;

  glm::mat4 view() const { return pose.fromWorld(); }
  // Reversed-Z projection (near -> 1, far or infinity -> 0; glClipControl ZERO_TO_ONE),
  // shifted so that the rasterizer's pixel centre samples rayDirection(centre + jitter).
  glm::mat4 projection() const;
  glm::mat4 unjitteredProjection() const;
  // Reversed-Z depth of a point at view-space distance d along -Z.
  float depthAt(float viewDistance) const;
};

glm::mat4 reversedZProjection(const FovTangents& fov, float znear, float zfar);

// An EyeCamera's rays with its rotation built once, for loops over an image's pixels
// (rayDirection builds it from the quaternion at every call, about half of its work).
class CameraRays {
 public:
  explicit CameraRays(const EyeCamera& camera);
  // camera.rayDirection(px, py) and camera.pixelRay(x, y), bit for bit.
  glm::vec3 direction(float px, float py) const;
  glm::vec3 pixelRay(int x, int y) const {
    return direction(x + 0.5f + jitter_.x, y + 0.5f + jitter_.y);
  }
  // A ray through the centre of pixel (x, y), not unit (the linear ray map,
  // rayBase + px rayDx + py rayDy): for what needs only the line, not the direction's length.
  glm::vec3 throughCentre(int x, int y) const {
    return base_ + (float(x) + 0.5f) * dx_ + (float(y) + 0.5f) * dy_;
  }
  // What direction() computes from, for its eight-lane form (trace/camera_lanes.h).
  struct Map {
    glm::mat3 rotation;
    float left, down;    // the field's tangents ...
    float spanX, spanY;  // ... and its extent, left + right and up + down
    glm::vec2 jitter;
    int width, height;
  };
  Map map() const {
    return {rotation_,           fov_.left, fov_.down, fov_.left + fov_.right,
            fov_.up + fov_.down, jitter_,   width_,    height_};
  }

 private:
  glm::vec3 base_, dx_, dy_;
  glm::mat3 rotation_;
  FovTangents fov_;
  glm::vec2 jitter_;
  int width_, height_;
};

// Halton (2, 3) point of a frame index, centred on the pixel: each coordinate in [-0.5, 0.5).
glm::vec2 haltonJitter(uint32_t frameIndex);

// Which numbers the renderers draw (--sampler): Owen-scrambled Sobol (core/sobol.h, the
// default) or the independent hashed numbers and Halton jitter of before, kept for A/B.
enum class SamplerKind : uint8_t { Random, Sobol };

// Where sample 'index' of a pixel sits, as an offset from the pixel centre in [-0.5, 0.5)^2.
// The index spans frames (frame f, sample s of n per frame: f * n + s), and one frame's
// G-buffer jitter is the position of index f. Sobol: the scrambled sequence's dimensions 0-1
// under one fixed scramble for every pixel, since the rasterizer jitters by shifting the
// whole projection; Random: haltonJitter(index).
glm::vec2 samplePosition(SamplerKind kind, uint32_t index);
const char* samplerName(SamplerKind kind);  // "random", "sobol"
float radicalInverse(uint32_t base, uint32_t index);

// Eye placement: each eye sits ipd / 2 along the head's local X; orientations equal the
// head's. The right eye's FOV mirrors the left's (outer and nasal tangents swap).
struct StereoRig {
  Pose head;
  float ipd = kDefaultIpd;
  FovTangents leftFov = FovTangents::dk2LeftEye();
  float znear = 0.05f;
  float zfar = 0.0f;
  EyeCamera eye(Eye e, int width, int height, glm::vec2 jitter = glm::vec2(0.0f)) const;
};

// Head pose of a scene camera (a glTF camera or a built-in view).
Pose poseOf(const Camera& camera);
// Pose at 'from' looking at 'at' with +Y up (falls back to +Z up when looking vertically).
Pose lookAt(const glm::vec3& from, const glm::vec3& at);

}  // namespace photovr
