// Hand-built G-buffers and inputs for the denoiser tests, and small CPU versions of the
// SVGF pass math (Schied et al. 2017) to compare the shaders with
// (../shared/STYLE.md, 9). Written from the paper, not from the shaders.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/packing.hpp>

#include "gl/denoiser.h"
#include "gl/gl_api.h"

namespace photovr::testing {

constexpr unsigned kBackground = 0xFFFFFFFFu;

inline float toHalf(float v) {
  return glm::unpackHalf1x16(glm::packHalf1x16(v));
}
inline glm::vec3 toHalf(glm::vec3 v) {
  return {toHalf(v.x), toHalf(v.y), toHalf(v.z)};
}
inline float luminance(glm::vec3 c) {
  return glm::dot(c, glm::vec3(0.2126f, 0.7152f, 0.0722f));
}

// One frame of synthetic input, both layers. Values that go into half-float textures are
// stored half-rounded, so CPU and GPU see the same numbers.
struct SyntheticFrame {
  int width = 0, height = 0;
  struct Layer {
    std::vector<glm::uvec4> visibility;
    std::vector<glm::vec3> normal;
    std::vector<float> roughness;
    std::vector<glm::vec2> motion;
    std::vector<float> depth;
    std::vector<glm::vec3> diffuse, specular, diffuseAlbedo, specularAlbedo, unfiltered;
  };
  std::array<Layer, 2> layer;

  SyntheticFrame(int w, int h) : width(w), height(h) {
    const size_t n = size_t(w) * h;
    for (Layer& l : layer) {
      l.visibility.assign(n, glm::uvec4(kBackground, 0, 0, 0));
      l.normal.assign(n, glm::vec3(0, 0, 1));
      l.roughness.assign(n, 1.0f);
      l.motion.assign(n, glm::vec2(0));
      l.depth.assign(n, 0.0f);
      for (auto* v : {&l.diffuse, &l.specular, &l.unfiltered}) v->assign(n, glm::vec3(0));
      for (auto* v : {&l.diffuseAlbedo, &l.specularAlbedo}) v->assign(n, glm::vec3(1));
    }
  }
  size_t index(int x, int y) const { return size_t(y) * width + x; }
  bool inside(int x, int y) const { return x >= 0 && y >= 0 && x < width && y < height; }
  void setSurface(int e, int x, int y, unsigned instance, unsigned triangle, float depth,
                  glm::vec3 normal) {
    const size_t i = index(x, y);
    layer[e].visibility[i] = glm::uvec4(instance, triangle, 0, 0);
    layer[e].depth[i] = depth;
    layer[e].normal[i] = toHalf(normal);
  }
  std::array<gl::NoisyEye, 2> eyes() const {
    std::array<gl::NoisyEye, 2> out;
    for (int e = 0; e < 2; ++e) {
      const Layer& l = layer[e];
      out[e] = {width,
                height,
                l.diffuse.data(),
                l.specular.data(),
                l.diffuseAlbedo.data(),
                l.specularAlbedo.data(),
                l.unfiltered.data()};
    }
    return out;
  }
};

// The G-buffer textures of a SyntheticFrame, in GBufferPass's formats.
class SyntheticGBuffer {
 public:
  SyntheticGBuffer(int w, int h) : w_(w), h_(h) {
    tex_[0] = make(GL_RGBA32UI);
    tex_[1] = make(GL_RGBA16F);
    tex_[2] = make(GL_RGBA16F);
    tex_[3] = make(GL_RG16F);
    tex_[4] = make(GL_DEPTH_COMPONENT32F);
  }
  ~SyntheticGBuffer() { gl::api::DeleteTextures(5, tex_); }
  SyntheticGBuffer(const SyntheticGBuffer&) = delete;
  SyntheticGBuffer& operator=(const SyntheticGBuffer&) = delete;

  void upload(const SyntheticFrame& f) {
    for (int e = 0; e < 2; ++e) {
      const SyntheticFrame::Layer& l = f.layer[e];
      std::vector<glm::vec4> normal(l.normal.size()), material(l.normal.size());
      for (size_t i = 0; i < normal.size(); ++i) {
        normal[i] = glm::vec4(l.normal[i], 0.0f);
        material[i] = glm::vec4(0.0f, l.roughness[i], 0.0f, 0.0f);
      }
      put(tex_[0], e, GL_RGBA_INTEGER, GL_UNSIGNED_INT, l.visibility.data());
      put(tex_[1], e, GL_RGBA, GL_FLOAT, normal.data());
      put(tex_[2], e, GL_RGBA, GL_FLOAT, material.data());
      put(tex_[3], e, GL_RG, GL_FLOAT, l.motion.data());
      put(tex_[4], e, GL_DEPTH_COMPONENT, GL_FLOAT, l.depth.data());
    }
  }
  gl::DenoiseGeometry geometry() const { return {tex_[0], tex_[1], tex_[2], tex_[3], tex_[4]}; }

 private:
  unsigned make(GLenum format) {
    GLuint t = 0;
    gl::api::CreateTextures(GL_TEXTURE_2D_ARRAY, 1, &t);
    gl::api::TextureStorage3D(t, 1, format, w_, h_, 2);
    // Integer and depth textures are incomplete (texelFetch returns 0) under a mipmapping
    // or linear filter; GBufferPass sets the same.
    gl::api::TextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl::api::TextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return t;
  }
  void put(GLuint t, int layer, GLenum format, GLenum type, const void* data) {
    gl::api::TextureSubImage3D(t, 0, 0, 0, layer, w_, h_, 1, format, type, data);
  }
  int w_, h_;
  GLuint tex_[5] = {};
};

// ---- CPU versions of the pass math -------------------------------------------------------

// Screen-space depth slope / depth, per axis the smaller one-sided difference.
inline glm::vec2 cpuRelativeGradient(const SyntheticFrame& f, int e, int x, int y) {
  const auto& d = f.layer[e].depth;
  const float c = d[f.index(x, y)];
  glm::vec2 g;
  for (int axis = 0; axis < 2; ++axis) {
    const int dx = axis == 0, dy = axis == 1;
    const float fwd = f.inside(x + dx, y + dy) ? d[f.index(x + dx, y + dy)] - c : 1e30f;
    const float bwd = f.inside(x - dx, y - dy) ? c - d[f.index(x - dx, y - dy)] : 1e30f;
    g[axis] = std::abs(fwd) < std::abs(bwd) ? fwd : bwd;
    if (std::abs(g[axis]) > 1e29f) g[axis] = 0.0f;
  }
  return g / c;
}

// SVGF eq. (3) and (4).
inline float cpuDepthWeight(const gl::DenoiseParams& p, float d, float dq, glm::vec2 grad,
                            glm::vec2 off) {
  return std::exp(-std::abs(d - dq) / (p.sigmaDepth * std::abs(glm::dot(grad, off)) + 1e-5f * d));
}
inline float cpuNormalWeight(const gl::DenoiseParams& p, glm::vec3 n, glm::vec3 nq) {
  return std::pow(std::max(0.0f, glm::dot(n, nq)), p.sigmaNormal);
}

inline glm::vec4 cpuLuminanceMoments(glm::vec3 d, glm::vec3 s) {
  const float ld = luminance(d), ls = luminance(s);
  return {ld, ld * ld, ls, ls * ls};
}

// SVGF §4.2: 7x7 depth- and normal-weighted luminance moments of this frame's samples.
inline glm::vec4 cpuSpatialMoments(const gl::DenoiseParams& p, const SyntheticFrame& f, int e,
                                   int x, int y) {
  const auto& l = f.layer[e];
  const size_t c = f.index(x, y);
  const glm::vec2 grad = cpuRelativeGradient(f, e, x, y) * l.depth[c];
  glm::vec4 sum(0);
  float wsum = 0;
  for (int v = -3; v <= 3; ++v)
    for (int u = -3; u <= 3; ++u) {
      if (!f.inside(x + u, y + v)) continue;
      const size_t q = f.index(x + u, y + v);
      if (l.visibility[q].x == kBackground) continue;
      const float w = cpuDepthWeight(p, l.depth[c], l.depth[q], grad, glm::vec2(u, v)) *
                      cpuNormalWeight(p, glm::normalize(l.normal[c]), glm::normalize(l.normal[q]));
      sum += w * cpuLuminanceMoments(l.diffuse[q], l.specular[q]);
      wsum += w;
    }
  return sum / wsum;
}

// What the GPU kept of the previous frame (read back after it ran).
struct PreviousFrame {
  const SyntheticFrame* frame;
  std::array<std::vector<glm::vec4>, 2> diffuse, specular, moments, aux;
};

struct CpuTemporal {
  glm::vec4 diffuse, specular;  // rgb, variance
  glm::vec4 moments;
  float length;
};

// |dn/dx| + |dn/dy|, per axis the smaller one-sided difference to the same instance.
inline float cpuNormalWidth(const SyntheticFrame& f, int e, int x, int y) {
  const auto& l = f.layer[e];
  const glm::vec3 n = glm::normalize(l.normal[f.index(x, y)]);
  float sum = 0.0f;
  for (int axis = 0; axis < 2; ++axis) {
    float best = 1e30f;
    for (int side = -1; side <= 1; side += 2) {
      const int qx = x + (axis == 0 ? side : 0), qy = y + (axis == 1 ? side : 0);
      if (!f.inside(qx, qy) || l.visibility[f.index(qx, qy)].x != l.visibility[f.index(x, y)].x)
        continue;
      best = std::min(best, glm::distance(n, glm::normalize(l.normal[f.index(qx, qy)])));
    }
    sum += best < 1e29f ? best : 0.0f;
  }
  return sum;
}

// Variance of a moving average of n unit-variance samples with alpha_k = max(alpha, 1/k).
inline float cpuSumSquaredWeights(const gl::DenoiseParams& p, float n) {
  float s = 0.0f;
  for (int k = 1; k <= int(n); ++k) {
    const float a = std::max(p.colorAlpha, 1.0f / float(k));
    s = (1.0f - a) * (1.0f - a) * s + a * a;
  }
  return s;
}

// SVGF §4.1: consistency of one previous-frame pixel (depth, normal, ids); the normal
// threshold grows with the normal's screen-space variation (Falcor).
inline bool cpuConsistent(const gl::DenoiseParams& p, const SyntheticFrame& cur,
                          const SyntheticFrame& prev, int e, int x, int y, int qx, int qy) {
  if (!prev.inside(qx, qy)) return false;
  const size_t c = cur.index(x, y), q = prev.index(qx, qy);
  const auto &a = cur.layer[e], &b = prev.layer[e];
  if (a.visibility[c].x != b.visibility[q].x) return false;
  if (p.requireSameTriangle && a.visibility[c].y != b.visibility[q].y) return false;
  const glm::vec2 g = cpuRelativeGradient(cur, e, x, y);
  const float z = 1.0f / a.depth[c], zq = 1.0f / std::max(b.depth[q], 1e-30f);
  const float slope = std::abs(g.x) + std::abs(g.y) + p.depthRejectEpsilon;
  if (std::abs(z - zq) / (z * slope) > p.depthRejectFactor) return false;
  return glm::distance(glm::normalize(a.normal[c]), glm::normalize(b.normal[q])) <=
         p.normalRejectDistance + p.normalRejectSlope * cpuNormalWidth(cur, e, x, y);
}

inline CpuTemporal cpuTemporal(const gl::DenoiseParams& p, const SyntheticFrame& cur,
                               const PreviousFrame* prev, int e, int x, int y) {
  const auto& l = cur.layer[e];
  const size_t c = cur.index(x, y);
  glm::vec3 d = l.diffuse[c], s = l.specular[c];
  glm::vec4 m = cpuLuminanceMoments(d, s);
  // Bilinear taps at the back-projected position, 3x3 fallback (as Falcor).
  glm::vec3 hd(0), hs(0);
  glm::vec4 hm(0);
  float hl = 0, sum = 0;
  auto tap = [&](int qx, int qy, float w) {
    const size_t q = prev->frame->index(qx, qy);
    hd += w * glm::vec3(prev->diffuse[e][q]);
    hs += w * glm::vec3(prev->specular[e][q]);
    hm += w * prev->moments[e][q];
    hl += w * prev->aux[e][q].x;
    sum += w;
  };
  if (prev) {
    const glm::vec2 pos = glm::vec2(x, y) + l.motion[c];
    const glm::ivec2 base = glm::ivec2(glm::floor(pos));
    const glm::vec2 fr = pos - glm::vec2(base);
    for (int i = 0; i < 4; ++i) {
      const int ox = i & 1, oy = i >> 1;
      const float w = (ox ? fr.x : 1 - fr.x) * (oy ? fr.y : 1 - fr.y);
      if (w > 0 && cpuConsistent(p, cur, *prev->frame, e, x, y, base.x + ox, base.y + oy))
        tap(base.x + ox, base.y + oy, w);
    }
    if (sum <= 0) {
      const glm::ivec2 centre = glm::ivec2(glm::floor(pos + 0.5f));
      for (int v = -1; v <= 1; ++v)
        for (int u = -1; u <= 1; ++u)
          if (cpuConsistent(p, cur, *prev->frame, e, x, y, centre.x + u, centre.y + v))
            tap(centre.x + u, centre.y + v, 1.0f);
    }
  }
  float len = 1;
  if (sum > 0) {
    len = std::min(std::floor(hl / sum + 0.5f) + 1.0f, float(p.historyCap));
    const float a = std::max(p.colorAlpha, 1 / len), am = std::max(p.momentsAlpha, 1 / len);
    d = glm::mix(hd / sum, d, a);
    s = glm::mix(hs / sum, s, a);
    m = glm::mix(hm / sum, m, am);
  }
  const glm::vec4 mv = len < p.temporalVarianceFrames ? cpuSpatialMoments(p, cur, e, x, y) : m;
  // The variance of the averaged colour: one sample's times sum w_k^2.
  const float s2 = cpuSumSquaredWeights(p, len);
  const float vd = std::max(0.0f, mv.y - mv.x * mv.x) * s2;
  const float vs = std::max(0.0f, mv.w - mv.z * mv.z) * s2;
  return {glm::vec4(d, vd), glm::vec4(s, vs), m, len};
}

// Firefly suppression (rank-conditioned rank selection, from above): each lobe's
// luminance clamped to 'factor' x the largest of its 3x3 neighbours on the same instance.
inline std::vector<glm::vec4> cpuFirefly(const gl::DenoiseParams& p, const SyntheticFrame& f, int e,
                                         const std::vector<glm::vec4>& in) {
  const auto& vis = f.layer[e].visibility;
  std::vector<glm::vec4> out = in;
  for (int y = 0; y < f.height; ++y)
    for (int x = 0; x < f.width; ++x) {
      const size_t c = f.index(x, y);
      if (vis[c].x == kBackground) continue;
      float hi = -1.0f;
      for (int v = -1; v <= 1; ++v)
        for (int u = -1; u <= 1; ++u)
          if ((u || v) && f.inside(x + u, y + v) && vis[f.index(x + u, y + v)].x == vis[c].x)
            hi = std::max(hi, luminance(glm::vec3(in[f.index(x + u, y + v)])));
      const float l = luminance(glm::vec3(in[c]));
      hi *= p.fireflyFactor;
      if (hi >= 0.0f && l > hi) out[c] = glm::vec4(glm::vec3(in[c]) * (hi / l), in[c].w);
    }
  return out;
}

// One a-trous iteration (SVGF §4.3 eqs. 1-2, weights §4.4 eqs. 3-5) of one layer.
// 'aux' is the GPU's (half-float) aux record, so both use the same stored gradient.
struct CpuAtrousOut {
  std::vector<glm::vec4> diffuse, specular;
};
inline CpuAtrousOut cpuAtrous(const gl::DenoiseParams& p, const SyntheticFrame& f, int e,
                              const std::vector<glm::vec4>& diffuse,
                              const std::vector<glm::vec4>& specular,
                              const std::vector<glm::vec4>& aux, int step) {
  const auto& l = f.layer[e];
  CpuAtrousOut out{diffuse, specular};
  const float h[3] = {3.0f / 8, 1.0f / 4, 1.0f / 16};
  for (int y = 0; y < f.height; ++y)
    for (int x = 0; x < f.width; ++x) {
      const size_t c = f.index(x, y);
      if (l.visibility[c].x == kBackground) continue;
      glm::vec2 var(0);
      float vw = 0;
      for (int v = -1; v <= 1; ++v)
        for (int u = -1; u <= 1; ++u) {
          if (!f.inside(x + u, y + v)) continue;
          const float w = (u ? 0.25f : 0.5f) * (v ? 0.25f : 0.5f);
          const size_t q = f.index(x + u, y + v);
          var += w * glm::vec2(diffuse[q].w, specular[q].w);
          vw += w;
        }
      const glm::vec2 phi =
          glm::vec2(p.sigmaLuminance, p.sigmaLuminanceSpecular) * glm::sqrt(var / vw) + 1e-10f;
      const glm::vec2 grad = glm::vec2(aux[c].y, aux[c].z) * l.depth[c];
      const float lobeSteps =
          std::min(p.specularMaxStep, p.specularFootprint * aux[c].w * aux[c].w);
      const bool spec = float(step) <= std::max(1.0f, lobeSteps);
      glm::vec4 sd(0), ss(0);
      glm::vec2 ws(0);
      for (int v = -2; v <= 2; ++v)
        for (int u = -2; u <= 2; ++u) {
          const int qx = x + u * step, qy = y + v * step;
          if (!f.inside(qx, qy)) continue;
          const size_t q = f.index(qx, qy);
          if (l.visibility[q].x == kBackground) continue;
          float w = h[std::abs(u)] * h[std::abs(v)];
          if (u || v)
            w *= cpuDepthWeight(p, l.depth[c], l.depth[q], grad, glm::vec2(u, v) * float(step)) *
                 cpuNormalWeight(p, glm::normalize(l.normal[c]), glm::normalize(l.normal[q]));
          auto add = [&](const std::vector<glm::vec4>& in, float phiL, glm::vec4& acc,
                         float& wsum) {
            const float wl =
                w * std::exp(-std::abs(luminance(glm::vec3(in[c])) - luminance(glm::vec3(in[q]))) /
                             phiL);
            acc += glm::vec4(wl * glm::vec3(in[q]), wl * wl * in[q].w);
            wsum += wl;
          };
          add(diffuse, phi.x, sd, ws.x);
          if (spec || (u == 0 && v == 0)) add(specular, phi.y, ss, ws.y);
        }
      out.diffuse[c] = glm::vec4(glm::vec3(sd) / ws.x, sd.w / (ws.x * ws.x));
      out.specular[c] = glm::vec4(glm::vec3(ss) / ws.y, ss.w / (ws.y * ws.y));
    }
  return out;
}

// The resolve (Karis 2014): history through a 4x4 Catmull-Rom kernel in the range-compressed
// space c / (1 + luma), clamped into the YCoCg box of the 3x3 neighbourhood, blended with
// weight max(alpha, 1 / n). 'history' is null on the first frame. Returns colour, count.
inline glm::vec3 cpuCompress(glm::vec3 c) {
  return c / (1.0f + luminance(c));
}
inline glm::vec3 cpuExpand(glm::vec3 c) {
  return c / std::max(1.0f - luminance(c), 1.0f / 65504.0f);
}
inline glm::vec3 cpuToYCoCg(glm::vec3 c) {
  return {0.25f * c.r + 0.5f * c.g + 0.25f * c.b, 0.5f * (c.r - c.b),
          -0.25f * c.r + 0.5f * c.g - 0.25f * c.b};
}
inline glm::vec3 cpuFromYCoCg(glm::vec3 c) {
  return {c.x + c.y - c.z, c.x + c.z, c.x - c.y - c.z};
}
inline glm::vec4 cpuCatmullRom(float t) {
  return {t * (-0.5f + t * (1.0f - 0.5f * t)), 1.0f + t * t * (-2.5f + 1.5f * t),
          t * (0.5f + t * (2.0f - 1.5f * t)), t * t * (-0.5f + 0.5f * t)};
}
inline glm::vec4 cpuResolve(const gl::DenoiseParams& p, const SyntheticFrame& f, int e, int x,
                            int y, const std::vector<glm::vec4>& color,
                            const std::vector<glm::vec4>* history) {
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (int v = -1; v <= 1; ++v)
    for (int u = -1; u <= 1; ++u)
      if (f.inside(x + u, y + v)) {
        const glm::vec3 c = cpuToYCoCg(glm::vec3(color[f.index(x + u, y + v)]));
        lo = glm::min(lo, c);
        hi = glm::max(hi, c);
      }
  glm::vec4 h(0);
  if (history) {
    const glm::vec2 pos = glm::vec2(x, y) + f.layer[e].motion[f.index(x, y)];
    const glm::vec2 base = glm::floor(pos), fr = pos - base;
    const glm::vec4 wx = cpuCatmullRom(fr.x), wy = cpuCatmullRom(fr.y);
    glm::vec4 sum(0);
    float wsum = 0;
    for (int v = 0; v < 4; ++v)
      for (int u = 0; u < 4; ++u) {
        const int qx = int(base.x) + u - 1, qy = int(base.y) + v - 1;
        const float w = wx[u] * wy[v];
        if (w == 0.0f || !f.inside(qx, qy)) continue;
        const glm::vec4 t = (*history)[f.index(qx, qy)];
        sum += w * glm::vec4(cpuCompress(glm::vec3(t)), t.w);
        wsum += w;
      }
    if (wsum > 0) h = glm::vec4(cpuExpand(glm::vec3(sum) / wsum), sum.w / wsum);
  }
  const float n = std::min(h.w + 1.0f, float(p.resolveHistoryCap));
  const float a = std::max(p.resolveAlpha, 1.0f / n);
  const glm::vec3 clamped = cpuFromYCoCg(glm::clamp(cpuToYCoCg(glm::vec3(h)), lo, hi));
  return {glm::mix(clamped, glm::vec3(color[f.index(x, y)]), a), n};
}

}  // namespace photovr::testing
