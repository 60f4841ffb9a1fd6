// The compositor tests' synthetic scene: a background plane z = -3 and a foreground square
// z = -1.5, traced analytically for any eye camera, and the check that a re-projection of
// it from pose A to a nearby pose B matches the scene traced at B (gl/compositor.h's grid
// re-projection and gl/timewarp.h's search both answer to it).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <vector>

#include <gtest/gtest.h>

#include "core/camera.h"

namespace photovr::testing {

inline constexpr int kW = 64, kH = 48;
inline const FovTangents kFov{0.55f, 0.5f, 0.45f, 0.4f};

// Scene: a background plane z = -3 (blue-ish, smooth pattern) and a foreground square
// z = -1.5, |x|, |y| <= 0.3 (red-ish). Smooth patterns keep the resampling error small.
inline glm::vec3 background(glm::vec3 p) {
  return {0.2f + 0.1f * std::sin(2.0f * p.x), 0.4f + 0.2f * std::sin(1.7f * p.y + 0.3f),
          0.8f + 0.15f * std::cos(1.3f * p.x + 1.1f * p.y)};
}
inline glm::vec3 foreground(glm::vec3 p) {
  return {0.85f + 0.1f * std::sin(6.0f * p.x), 0.3f + 0.2f * std::cos(5.0f * p.y), 0.1f};
}

struct Hit {
  glm::vec3 color;
  float distance;  // view distance (along the camera's -Z)
  bool front;
};

// Ray through window coordinates (px, py) of a camera, intersected with the scene.
inline Hit trace(const EyeCamera& cam, float px, float py) {
  const glm::vec3 eyeDir(-cam.fov.left + px * (cam.fov.left + cam.fov.right) / cam.width,
                         -cam.fov.down + py * (cam.fov.up + cam.fov.down) / cam.height, -1.0f);
  const glm::vec3 d = glm::mat3_cast(cam.pose.orientation) * eyeDir;
  const glm::vec3 o = cam.pose.position;
  const float tf = (-1.5f - o.z) / d.z;
  const glm::vec3 pf = o + tf * d;
  if (tf > 0.0f && std::abs(pf.x) <= 0.3f && std::abs(pf.y) <= 0.3f)
    return {foreground(pf), tf, true};
  const float tb = (-3.0f - o.z) / d.z;
  return {background(o + tb * d), tb, false};
}

struct EyeImage {  // of the two-plane scene
  std::vector<glm::vec4> color;
  std::vector<float> depth;
  std::vector<uint8_t> front;
};

inline EyeImage render(const EyeCamera& cam) {
  EyeImage img;
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      const Hit h = trace(cam, x + 0.5f + cam.jitter.x, y + 0.5f + cam.jitter.y);
      img.color.emplace_back(h.color, 1.0f);
      img.depth.push_back(cam.depthAt(h.distance));
      img.front.push_back(h.front);
    }
  return img;
}

inline EyeCamera camera(const Pose& pose, glm::vec2 jitter = glm::vec2(0.0f)) {
  EyeCamera c;
  c.pose = pose;
  c.fov = kFov;
  c.width = kW;
  c.height = kH;
  c.jitter = jitter;
  return c;
}

struct ReprojectedEye {
  std::vector<glm::vec4> color;  // alpha: origin (gl/compositor.h: 1, 0.5 filled, 0 uncovered)
  std::vector<float> depth;      // reversed-Z at pose B
};

using Reprojection = std::function<std::array<ReprojectedEye, 2>(
    const std::array<EyeImage, 2>& in, const std::array<EyeCamera, 2>& from,
    const std::array<EyeCamera, 2>& to)>;

// Re-projects the two-plane scene from pose A to a nearby pose B with 'reproject' and
// compares with the scene rendered at B. 'margin' pixels around the square's silhouette are
// left out of the interior statistics (1 + the grid step for the grid re-projection).
inline void checkNearbyPose(const char* label, int margin, const Reprojection& reproject) {
  Pose a;
  Pose b;
  b.position = {0.1f, 0.03f, -0.02f};  // 2 px of parallax between the planes
  b.orientation = glm::angleAxis(glm::radians(2.5f), glm::vec3(0, 1, 0)) *
                  glm::angleAxis(glm::radians(-1.0f), glm::vec3(1, 0, 0));
  const std::array<EyeCamera, 2> from = {camera(a, {0.2f, 0.3f}), camera(a)};
  const std::array<EyeCamera, 2> to = {camera(b, {-0.1f, 0.2f}), camera(b)};
  const std::array<EyeImage, 2> in = {render(from[0]), render(from[1])};
  const std::array<ReprojectedEye, 2> result = reproject(in, from, to);
  for (int e = 0; e < 2; ++e) {
    const EyeImage truth = render(to[e]);
    const auto& out = result[e].color;
    const auto& depth = result[e].depth;
    double errValid = 0.0, depthErr = 0.0, errInterior = 0.0, maxInterior = 0.0;
    int nInterior = 0;
    int valid = 0, filled = 0, uncovered = 0, filledBackground = 0;
    // Expected disocclusion: B pixels showing background that A does not see (hidden by
    // the square, or outside A's frustum).
    int expected = 0;
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        const size_t i = size_t(y) * kW + x;
        const glm::vec4 o = out[i];
        if (o.a > 0.75f) {
          ++valid;
          const glm::vec3 d = glm::abs(glm::vec3(o) - glm::vec3(truth.color[i]));
          errValid += (d.x + d.y + d.z) / 3.0;
          // Interior: the truth's neighbourhood of radius 'margin' shows one surface (away
          // from the square's silhouette, where any pixel-sampled edge is off by up to a
          // pixel, and a grid cell across the edge reaches 'step' pixels further).
          const int m = margin;
          bool interior = x >= m && y >= m && x + m < kW && y + m < kH;
          for (int dy = -m; dy <= m && interior; ++dy)
            for (int dx = -m; dx <= m; ++dx)
              interior = interior && truth.front[i + dy * kW + dx] == truth.front[i];
          if (interior) {
            ++nInterior;
            errInterior += (d.x + d.y + d.z) / 3.0;
            maxInterior = std::max(maxInterior, double(std::max(d.x, std::max(d.y, d.z))));
            depthErr += std::abs(depth[i] - truth.depth[i]) / truth.depth[i];
          }
        } else if (o.a > 0.25f) {
          ++filled;
          filledBackground += o.b > o.r;  // background is blue-ish, the square red-ish
        } else {
          ++uncovered;
        }
        // Where is B's hit as seen from A?
        const EyeCamera& cb = to[e];
        const glm::vec3 eyeDir(
            -cb.fov.left + (x + 0.5f + cb.jitter.x) * (cb.fov.left + cb.fov.right) / kW,
            -cb.fov.down + (y + 0.5f + cb.jitter.y) * (cb.fov.up + cb.fov.down) / kH, -1.0f);
        const glm::vec3 world = cb.pose.position + glm::mat3_cast(cb.pose.orientation) * eyeDir *
                                                       (cb.znear / truth.depth[i]);
        const glm::vec4 inA = from[e].view() * glm::vec4(world, 1.0f);
        const float tx = inA.x / -inA.z, ty = inA.y / -inA.z;
        const float ax = (tx + kFov.left) * kW / (kFov.left + kFov.right) - from[e].jitter.x;
        const float ay = (ty + kFov.down) * kH / (kFov.up + kFov.down) - from[e].jitter.y;
        if (ax < 0 || ay < 0 || ax > kW || ay > kH) {
          ++expected;
        } else if (!truth.front[i]) {
          const Hit h = trace(from[e], ax, ay);
          expected += h.front;
        }
      }
    const int n = kW * kH;
    const double meanErr = errValid / std::max(valid, 1);
    const double measured = double(filled + uncovered) / n;
    std::printf(
        "reprojection (%s) eye %d: mean abs colour error %.2e over %d re-projected "
        "pixels; interior "
        "(%d px) mean %.2e, max %.2e, mean relative depth error %.2e; disoccluded %.4f (filled %d, "
        "uncovered %d; %d filled from the background), analytic %.4f\n",
        label, e, meanErr, valid, nInterior, errInterior / nInterior, maxInterior,
        depthErr / nInterior, measured, filled, uncovered, filledBackground, double(expected) / n);
    EXPECT_LT(meanErr, 0.03);
    EXPECT_LT(errInterior / nInterior, 1e-3);
    EXPECT_LT(maxInterior, 5e-3);
    EXPECT_LT(depthErr / nInterior, 1e-4);
    EXPECT_GT(filled, 0);
    EXPECT_GE(filledBackground, filled * 9 / 10);
    EXPECT_NEAR(measured, double(expected) / n, 0.3 * double(expected) / n + 8.0 / n);
  }
}

}  // namespace photovr::testing
