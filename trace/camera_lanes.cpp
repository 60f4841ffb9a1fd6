#include "trace/camera_lanes.h"

#include <vector>

#include "trace/lanes.h"
#include "trace/scratch.h"

#pragma GCC diagnostic ignored "-Wpsabi"  // see trace/lanes.h

namespace photovr {
namespace {

using lanes::F8;
using lanes::V3;

struct alignas(32) RayLanes8 {  // 32: see trace/hit_geometry.cpp's Lanes8
  F8 px, py;                    // window coordinates of the samples
  V3<F8> dir;
};
static_assert(alignof(RayLanes8) == 32);

// CameraRays::direction, lane by lane, in its order of operations: the eye-space point
// (-left + px (left + right) / width, -down + py (up + down) / height, -1), rotated as
// glm's mat3 * vec3 ((m0 x + m1 y) + m2 z), then glm::normalize.
__attribute__((target_clones("avx2", "default"))) void directionLanes(RayLanes8* groups,
                                                                      size_t count,
                                                                      const CameraRays::Map& m) {
  const float w = float(m.width), h = float(m.height);
  const glm::mat3& r = m.rotation;
  for (size_t g = 0; g < count; ++g) {
    RayLanes8& l = groups[g];
    const F8 ex = -m.left + l.px * m.spanX / w, ey = -m.down + l.py * m.spanY / h;
    const V3<F8> d{r[0][0] * ex + r[1][0] * ey + r[2][0] * -1.0f,
                   r[0][1] * ex + r[1][1] * ey + r[2][1] * -1.0f,
                   r[0][2] * ex + r[1][2] * ey + r[2][2] * -1.0f};
    l.dir = lanes::normalized(d);
  }
}

// Fills groups' sample positions with position(i) for i in [0, n) (the last group's unused
// lanes with 0), traces them and hands lane i's direction to out[i].
template <typename Position>
void directionsOf(const CameraRays::Map& m, size_t n, Position position, std::span<glm::vec3> out) {
  thread_local std::vector<RayLanes8> groups;
  growTo(groups, (n + 7) / 8);
  for (size_t i = 0; i < n; ++i) {
    const glm::vec2 p = position(i);
    groups[i / 8].px[i % 8] = p.x, groups[i / 8].py[i % 8] = p.y;
  }
  for (size_t i = n; i % 8 != 0; ++i) groups[i / 8].px[i % 8] = groups[i / 8].py[i % 8] = 0.0f;
  directionLanes(groups.data(), (n + 7) / 8, m);
  for (size_t i = 0; i < n; ++i) {
    const RayLanes8& l = groups[i / 8];
    out[i] = {l.dir.x[i % 8], l.dir.y[i % 8], l.dir.z[i % 8]};
  }
}

}  // namespace

void pixelRays(const CameraRays& rays, size_t begin, std::span<glm::vec3> out) {
  const CameraRays::Map m = rays.map();
  // Walked, not divided: x and y of each pixel from the previous one's.
  int x = int(begin % size_t(m.width)), y = int(begin / size_t(m.width));
  directionsOf(
      m, out.size(),
      [&](size_t) {
        const glm::vec2 p(x + 0.5f + m.jitter.x, y + 0.5f + m.jitter.y);  // pixelRay's sample
        if (++x == m.width) x = 0, ++y;
        return p;
      },
      out);
}

void sampleRays(const CameraRays& rays, std::span<const glm::vec2> samples,
                std::span<glm::vec3> out) {
  directionsOf(
      rays.map(), samples.size(), [&](size_t i) { return samples[i]; }, out);
}

}  // namespace photovr
