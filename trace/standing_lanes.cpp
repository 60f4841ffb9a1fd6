#include "trace/standing_lanes.h"

#include <cstdint>
#include <vector>

#include "trace/lanes.h"
#include "trace/scratch.h"

#pragma GCC diagnostic ignored "-Wpsabi"  // see trace/lanes.h

namespace photovr {
namespace {

using lanes::F8;
using lanes::I8;
using lanes::select;
using lanes::V3;

struct alignas(32) StandingLanes8 {  // 32: see trace/hit_geometry.cpp's Lanes8
  V3<F8> position, normal, centreRay;
  I8 glass;  // transmission > 0: no standing pixel
  I8 pixel;  // out: the left pixel, or -1 (kNoLeftPixel)
  F8 footprint2;
};
static_assert(alignof(StandingLanes8) == 32);

// What standingPixelOf takes from the left window and the right eye, for every lane.
struct Uniforms {
  V3<float> leftEye, rightEye;
  float offsetX, offsetY;
  float pixelAngle;
  float m[3][3];  // toWindow, glm's [column][row]
  float width, height;
  int32_t widthPixels;
};

template <typename T>
[[gnu::always_inline]] inline V3<T> minusPoint(const V3<T>& a, const V3<float>& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}

// standingPixelOf and its leftWindowPoint (trace/stereo_reuse.cpp), lane by lane, in their
// order of operations, with selects for their early returns.
__attribute__((target_clones("avx2", "default"))) void standingLanes(StandingLanes8* groups,
                                                                     size_t count,
                                                                     const Uniforms& u) {
  for (size_t g = 0; g < count; ++g) {
    StandingLanes8& l = groups[g];
    const V3<F8> offset = minusPoint(l.position, u.leftEye);
    const F8 footprint2 = u.pixelAngle * u.pixelAngle * lanes::dot(offset, offset);
    const V3<F8>& n = l.normal;
    const F8 t = lanes::dot(minusPoint(l.position, u.rightEye), n) / lanes::dot(l.centreRay, n);
    const V3<F8> centre{u.rightEye.x + t * l.centreRay.x, u.rightEye.y + t * l.centreRay.y,
                        u.rightEye.z + t * l.centreRay.z};
    const V3<F8> d = lanes::minus(centre, l.position);
    const I8 onPlane = (t > 0.0f) & (lanes::dot(d, d) <= 64.0f * footprint2);  // kCentreReach^2
    const V3<F8> to = minusPoint(
        V3<F8>{select(onPlane, centre.x, l.position.x), select(onPlane, centre.y, l.position.y),
               select(onPlane, centre.z, l.position.z)},
        u.leftEye);
    // glm's mat3 * vec3: (m0 x + m1 y) + m2 z, row by row.
    const F8 wx = u.m[0][0] * to.x + u.m[1][0] * to.y + u.m[2][0] * to.z;
    const F8 wy = u.m[0][1] * to.x + u.m[1][1] * to.y + u.m[2][1] * to.z;
    const F8 wz = u.m[0][2] * to.x + u.m[1][2] * to.y + u.m[2][2] * to.z;
    const F8 zero{};
    const F8 px = wx / wz - select(onPlane, zero, zero + u.offsetX);
    const F8 py = wy / wz - select(onPlane, zero, zero + u.offsetY);
    const I8 ok = (l.glass == 0) & (wz > 0.0f) & (px >= 0.0f) & (py >= 0.0f) & (px < u.width) &
                  (py < u.height);
    // Truncated only where ok (in [0, size)): elsewhere the conversion's value is unused.
    const I8 x = __builtin_convertvector(select(ok, px, zero), I8);
    const I8 y = __builtin_convertvector(select(ok, py, zero), I8);
    l.pixel = ok ? y * u.widthPixels + x : I8{} - 1;
    l.footprint2 = select(ok, footprint2, zero);
  }
}

V3<float> toV3(const glm::vec3& v) {
  return {v.x, v.y, v.z};
}

template <typename T>
void setLane(V3<T>& lanes, size_t k, const glm::vec3& v) {
  lanes.x[k] = v.x, lanes.y[k] = v.y, lanes.z[k] = v.z;
}

}  // namespace

void standingPixelsOf(const EyeWindow& left, const glm::vec3& eye, const glm::vec2& offset,
                      std::span<const StandingJob> jobs) {
  Uniforms u;
  u.leftEye = toV3(left.camera.pose.position);
  u.rightEye = toV3(eye);
  u.offsetX = offset.x, u.offsetY = offset.y;
  u.pixelAngle = left.pixelAngle;
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) u.m[c][r] = left.toWindow[c][r];
  u.width = float(left.camera.width), u.height = float(left.camera.height);
  u.widthPixels = int32_t(left.camera.width);
  const size_t n = jobs.size(), groupCount = (n + 7) / 8;
  thread_local std::vector<StandingLanes8> groups;
  growTo(groups, groupCount);
  for (size_t i = 0; i < groupCount * 8; ++i) {
    StandingLanes8& l = groups[i / 8];
    const size_t k = i % 8;
    if (i >= n) {  // an unused lane: a glass hit, which has no standing pixel
      l.glass[k] = -1;
      setLane(l.position, k, glm::vec3(0.0f)), setLane(l.normal, k, glm::vec3(0.0f, 0.0f, 1.0f));
      setLane(l.centreRay, k, glm::vec3(0.0f, 0.0f, -1.0f));
      continue;
    }
    const SurfaceHit& hit = *jobs[i].hit;
    l.glass[k] = hit.bsdf.transmission > 0.0f ? -1 : 0;
    setLane(l.position, k, hit.position);
    setLane(l.normal, k, hit.geometricNormal);
    setLane(l.centreRay, k, jobs[i].centreRay);
  }
  standingLanes(groups.data(), groupCount, u);
  for (size_t i = 0; i < n; ++i) {
    const StandingLanes8& l = groups[i / 8];
    StandingPixel& s = *jobs[i].out;
    s.pixel = uint32_t(l.pixel[i % 8]);
    s.footprint2 = l.footprint2[i % 8];
  }
}

}  // namespace photovr
