#include "core/camera.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "core/sobol.h"

namespace photovr {

glm::mat4 Pose::toWorld() const {
  return glm::translate(glm::mat4(1.0f), position) * glm::mat4_cast(orientation);
}

glm::mat4 Pose::fromWorld() const {
  const glm::mat4 r = glm::mat4_cast(glm::conjugate(orientation));
  return r * glm::translate(glm::mat4(1.0f), -position);
}

FovTangents FovTangents::symmetric(float yfov, float aspect) {
  const float t = std::tan(0.5f * yfov);
  return {t * aspect, t * aspect, t, t};
}

FovTangents FovTangents::widened(float radians) const {
  // An edge tan = t holds directions of azimuth atan(t) about the edge's axis (the left and
  // right edges: about y), at every elevation. A cone of half-angle a around a direction at
  // elevation b reaches azimuths asin(sin a / cos b) further (right spherical triangle
  // pole-centre-tangent point); the field's corner has the highest elevation,
  // tan b = corner / sqrt(1 + t^2).
  const double a = radians;
  const auto out = [a](double t, double corner) {
    const double b = std::atan(corner / std::sqrt(1.0 + t * t));
    const double turn = std::asin(std::min(1.0, std::sin(a) / std::cos(b)));
    return float(std::tan(std::min(std::atan(t) + turn, 1.5)));  // 1.5 rad: 86 deg, finite
  };
  const double vertical = std::max(up, down), horizontal = std::max(left, right);
  return {out(left, vertical), out(right, vertical), out(up, horizontal), out(down, horizontal)};
}

StereoLayout StereoLayout::forField(const FovTangents& field, int fieldWidth, int fieldHeight,
                                    float overscanRadians) {
  StereoLayout l;
  l.overscan = overscanRadians;
  l.leftField = field;
  l.leftFov = field.widened(overscanRadians);
  // The same pixels per tan-angle as the field; rounded up so the field stays inside.
  const auto grown = [overscanRadians](int n, float span, float widened) {
    return overscanRadians == 0.0f ? n : int(std::ceil(n * double(widened) / span - 1e-9));
  };
  l.width = grown(fieldWidth, field.left + field.right, l.leftFov.left + l.leftFov.right);
  l.height = grown(fieldHeight, field.up + field.down, l.leftFov.up + l.leftFov.down);
  return l;
}

glm::vec3 EyeCamera::rayBase() const {
  const glm::mat3 r = glm::mat3_cast(pose.orientation);
  return r * glm::vec3(-fov.left, -fov.down, -1.0f);
}

glm::vec3 EyeCamera::rayDx() const {
  return glm::mat3_cast(pose.orientation) * glm::vec3((fov.left + fov.right) / width, 0, 0);
}

glm::vec3 EyeCamera::rayDy() const {
  return glm::mat3_cast(pose.orientation) * glm::vec3(0, (fov.up + fov.down) / height, 0);
}

glm::vec3 EyeCamera::rayDirection(float px, float py) const {
  return CameraRays(*this).direction(px, py);
}

CameraRays::CameraRays(const EyeCamera& camera)
    : base_(camera.rayBase()),
      dx_(camera.rayDx()),
      dy_(camera.rayDy()),
      rotation_(glm::mat3_cast(camera.pose.orientation)),
      fov_(camera.fov),
      jitter_(camera.jitter),
      width_(camera.width),
      height_(camera.height) {}

glm::vec3 CameraRays::direction(float px, float py) const {
  // Composed in eye space, then rotated: the same arithmetic as rayBase + px*dx + py*dy up
  // to rounding; the shaders use the rayBase form, the tracer this one (both float).
  const glm::vec3 d(-fov_.left + px * (fov_.left + fov_.right) / width_,
                    -fov_.down + py * (fov_.up + fov_.down) / height_, -1.0f);
  return glm::normalize(rotation_ * d);
}

glm::mat4 reversedZProjection(const FovTangents& fov, float n, float f) {
  // x_ndc = (2 x_e / (-z_e) + (l - r)) / (l + r) in tangent units; depth = A + B / (-z_e)
  // with depth(n) = 1 and depth(f) = 0 (infinite far: A = 0, B = n).
  glm::mat4 p(0.0f);
  p[0][0] = 2.0f / (fov.left + fov.right);
  p[1][1] = 2.0f / (fov.up + fov.down);
  p[2][0] = (fov.right - fov.left) / (fov.left + fov.right);
  p[2][1] = (fov.up - fov.down) / (fov.up + fov.down);
  p[2][3] = -1.0f;
  if (f > 0.0f) {
    p[2][2] = n / (f - n);
    p[3][2] = n * f / (f - n);
  } else {
    p[2][2] = 0.0f;
    p[3][2] = n;
  }
  return p;
}

glm::mat4 EyeCamera::unjitteredProjection() const {
  return reversedZProjection(fov, znear, zfar);
}

glm::mat4 EyeCamera::projection() const {
  // Shifting NDC by -2j/size moves what lands on the pixel centre c to the direction of
  // c + j: the rasterizer then samples the same position as pixelRay().
  glm::mat4 shift(1.0f);
  shift[3][0] = -2.0f * jitter.x / width;
  shift[3][1] = -2.0f * jitter.y / height;
  return shift * unjitteredProjection();
}

float EyeCamera::depthAt(float d) const {
  if (zfar > 0.0f) return (znear * zfar / (zfar - znear)) / d - znear / (zfar - znear);
  return znear / d;
}

float radicalInverse(uint32_t base, uint32_t index) {
  double inv = 1.0 / base, f = inv, r = 0.0;
  for (; index > 0; index /= base, f *= inv) r += f * (index % base);
  return float(r);
}

glm::vec2 haltonJitter(uint32_t frameIndex) {
  // Index + 1 skips the (0, 0) point so frame 0 is not biased to the pixel corner.
  return glm::vec2(radicalInverse(2, frameIndex + 1), radicalInverse(3, frameIndex + 1)) - 0.5f;
}

glm::vec2 samplePosition(SamplerKind kind, uint32_t index) {
  if (kind == SamplerKind::Random) return haltonJitter(index);
  // Any fixed seed: the positions are a function of the index alone, as Halton's were, so
  // that renderers with different --seed still sample the same pixel positions.
  constexpr uint32_t kPixelSeed = 0x9e3779b9u;
  const glm::uvec2 p = scrambledSobol2D(index, kPixelSeed);
  // 24-bit fractions: exact in float, largest 1 - 2^-24, so the offset stays below 0.5.
  return glm::vec2(float(p.x >> 8), float(p.y >> 8)) * 0x1p-24f - 0.5f;
}

const char* samplerName(SamplerKind kind) {
  return kind == SamplerKind::Random ? "random" : "sobol";
}

EyeCamera StereoRig::eye(Eye e, int width, int height, glm::vec2 jitter) const {
  EyeCamera cam;
  const float side = e == Eye::Left ? -0.5f : 0.5f;
  cam.pose.orientation = head.orientation;
  cam.pose.position = head.position + head.orientation * glm::vec3(side * ipd, 0, 0);
  cam.fov = e == Eye::Left ? leftFov : leftFov.mirrored();
  cam.znear = znear;
  cam.zfar = zfar;
  cam.width = width;
  cam.height = height;
  cam.jitter = jitter;
  return cam;
}

Pose poseOf(const Camera& camera) {
  return {camera.position, camera.orientation};
}

Pose lookAt(const glm::vec3& from, const glm::vec3& at) {
  const glm::vec3 forward = glm::normalize(at - from);
  const glm::vec3 up = std::abs(forward.y) > 0.999f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
  const glm::vec3 right = glm::normalize(glm::cross(forward, up));
  const glm::vec3 trueUp = glm::cross(right, forward);
  const glm::mat3 basis(right, trueUp, -forward);
  return {from, glm::normalize(glm::quat_cast(basis))};
}

}  // namespace photovr
