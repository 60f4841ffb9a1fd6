// Image comparison for the golden tests, in the manner of Filament's renderdiff: a pixel
// fails when any of its channels differs from the golden by more than a threshold, and an
// image fails when more than an allowed fraction of its pixels fail.
//
// The difference of one channel is |actual - golden| / max(1, |golden|): absolute for
// values up to 1 (every 8-bit image, depth, normals, most radiance), relative above, so
// one threshold means the same few float steps on a lamp of radiance 50 as on a wall of
// 0.5. Header-only: every .cpp in tests/golden/ is a test source (tests/CMakeLists.txt).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "core/image_io.h"

namespace photovr::golden {

struct Tolerance {
  float maxDiff = 0.0f;             // per channel, in the measure above
  double maxFailingFraction = 0.0;  // of the image's pixels
};

struct Comparison {
  bool sameShape = false;  // width, height and channels agree
  size_t pixels = 0;
  size_t differing = 0;  // pixels not bit-identical
  size_t failing = 0;    // pixels with a channel beyond the threshold
  float maxDiff = 0.0f;  // the largest channel difference, in the measure above
  int maxX = 0, maxY = 0;

  double failingFraction() const { return pixels ? double(failing) / double(pixels) : 1.0; }
  bool passes(const Tolerance& t) const {
    return sameShape && failingFraction() <= t.maxFailingFraction;
  }
};

// One channel's difference; a NaN or infinity on one side only is infinitely different.
inline float channelDiff(float golden, float actual) {
  if (golden == actual || (std::isnan(golden) && std::isnan(actual))) return 0.0f;
  const float d = std::abs(actual - golden) / std::max(1.0f, std::abs(golden));
  return std::isfinite(d) ? d : std::numeric_limits<float>::infinity();
}

inline float pixelDiff(const ImageF& golden, const ImageF& actual, int x, int y) {
  const float* g = golden.at(x, y);
  const float* a = actual.at(x, y);
  float d = 0.0f;
  for (int c = 0; c < golden.channels; ++c) d = std::max(d, channelDiff(g[c], a[c]));
  return d;
}

inline bool sameShape(const ImageF& a, const ImageF& b) {
  return a.width == b.width && a.height == b.height && a.channels == b.channels;
}

inline Comparison compareImages(const ImageF& golden, const ImageF& actual, const Tolerance& t) {
  Comparison r;
  r.sameShape = sameShape(golden, actual);
  if (!r.sameShape) return r;
  r.pixels = size_t(golden.width) * size_t(golden.height);
  for (int y = 0; y < golden.height; ++y)
    for (int x = 0; x < golden.width; ++x) {
      const float d = pixelDiff(golden, actual, x, y);
      r.differing += d > 0.0f;
      r.failing += d > t.maxDiff;
      if (d > r.maxDiff) r.maxDiff = d, r.maxX = x, r.maxY = y;
    }
  return r;
}

// The golden's luminance, tone-mapped into [0, 1] (x / (1 + x) keeps HDR values apart).
inline float displayLuminance(const ImageF& image, int x, int y) {
  const float* p = image.at(x, y);
  const float l = image.channels >= 3 ? 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2] : p[0];
  return std::isfinite(l) && l > 0.0f ? l / (1.0f + l) : 0.0f;
}

// Failing pixels red (brighter the larger the difference), pixels that differ within the
// threshold blue, identical ones the golden in dark grey. Both images have one shape.
inline Image8 diffImage(const ImageF& golden, const ImageF& actual, const Tolerance& t) {
  Image8 out(golden.width, golden.height, 3);
  const Comparison c = compareImages(golden, actual, t);
  for (int y = 0; y < golden.height; ++y)
    for (int x = 0; x < golden.width; ++x) {
      const float d = pixelDiff(golden, actual, x, y);
      uint8_t* o = out.at(x, y);
      const uint8_t grey = uint8_t(std::lround(96.0f * displayLuminance(golden, x, y)));
      o[0] = o[1] = o[2] = grey;
      if (d > t.maxDiff) {
        const float s =
            std::isfinite(c.maxDiff) && c.maxDiff > 0 ? std::min(1.0f, d / c.maxDiff) : 1;
        o[0] = uint8_t(std::lround(128.0f + 127.0f * s)), o[1] = o[2] = 0;
      } else if (d > 0.0f) {
        o[0] = o[1] = 0, o[2] = 200;
      }
    }
  return out;
}

}  // namespace photovr::golden
