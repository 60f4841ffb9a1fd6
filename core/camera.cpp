#include "core/camera.h"

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

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
  // Composed in eye space, then rotated: the same arithmetic as rayBase + px*dx + py*dy up
  // to rounding; the shaders use the rayBase form, the tracer this one (both float).
  const glm::vec3 d(-fov.left + px * (fov.left + fov.right) / width,
                    -fov.down + py * (fov.up + fov.down) / height, -1.0f);
  return glm::normalize(glm::mat3_cast(pose.orientation) * d);
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
