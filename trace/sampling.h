// Sampling building blocks for the tracer: shading frames, warps from [0,1)^2 to
// directions with their pdfs, the MIS power heuristic, and piecewise-constant 1D/2D
// distributions (Pharr, Jakob & Humphreys, "Physically Based Rendering", 4th ed., sec.
// A.5 and 13.6 -- "pbrt" below). Pure math: no Embree, no scene.
#pragma once

#include <algorithm>
#include <cmath>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace photovr {

inline constexpr float kPi = 3.14159265358979323846f;
inline constexpr float kInvPi = 0.31830988618379067154f;
inline constexpr float kInv2Pi = 0.15915494309189533577f;
inline constexpr float kInv4Pi = 0.07957747154594766788f;
// The largest float below 1; samplers clamp to it so a warp of u in [0,1) never returns
// the excluded end of its domain.
inline constexpr float kOneMinusEpsilon = 0x1.fffffep-1f;

inline bool isFinite(float v) {
  return v - v == 0.0f;
}  // false for NaN and +-Inf
inline bool isFinite(const glm::vec2& v) {
  return isFinite(v.x) && isFinite(v.y);
}
inline bool isFinite(const glm::vec3& v) {
  return isFinite(v.x) && isFinite(v.y) && isFinite(v.z);
}

// Rec. ITU-R BT.709 luminance of linear RGB; the weights used to turn colours into the
// scalar importance of lobes and environment pixels.
inline float luminance(const glm::vec3& c) {
  return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b;
}

// c >= std::cos(a) for a in [0, 1], to the bit, calling cos only where c lies between its
// Taylor bounds 1 - a^2/2 <= cos(a) <= 1 - a^2/2 + a^4/24, each widened by 4e-7 (several
// float ulps below 1, for their rounding and cos's). Where c is a cosine between two views
// and a a lobe's width, it is rarely that close.
inline bool atLeastCosOf(float c, float a) {
  const float lower = 1.0f - 0.5f * a * a, upper = lower + a * a * a * a * (1.0f / 24.0f);
  if (c < lower - 4e-7f) return false;
  if (c > upper + 4e-7f) return true;
  return c >= std::cos(a);
}

inline float safeSqrt(float v) {
  return std::sqrt(std::max(0.0f, v));
}

// The cell of n equal cells over [0,1] that x falls in, clamped to [0, n-1]; NaN -> 0
// (a float-to-int conversion of NaN or of an out-of-range value is undefined).
inline int cellIndex(float x, int n) {
  const float c = x > 0.0f ? std::min(x, 1.0f) * float(n) : 0.0f;
  return std::min(int(c), n - 1);
}

// Duff, Burgess, Christensen, Hery, Kensler, Liani & Villemin, "Building an Orthonormal
// Basis, Revisited", JCGT 6(1), 2017, listing 3: branchless, accurate for every unit n
// including n.z = -1 (the case Frisvad's original method gets wrong). Inline, as is
// Frame::fromZ: every shaded vertex builds frames, and a frame returned from another
// translation unit through the stack stalled its reader on store forwarding (the caller
// loads 8 bytes where the callee stored 4; docs/ARCHITECTURE.md, "Structs are written
// where they are read").
inline void orthonormalBasis(const glm::vec3& n, glm::vec3& b1, glm::vec3& b2) {
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z);
  const float b = n.x * n.y * a;
  b1 = glm::vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
  b2 = glm::vec3(b, sign + n.y * n.y * a, -n.y);
}

// A right-handed orthonormal frame with z = the given unit normal.
struct Frame {
  glm::vec3 x{1, 0, 0}, y{0, 1, 0}, z{0, 0, 1};

  static Frame fromZ(const glm::vec3& n) {
    Frame f;
    f.setZ(n);
    return f;
  }
  // fromZ(n) in place: a frame assigned from fromZ went through the stack, and its copy's
  // 16-byte loads of what orthonormalBasis stored in 8 and 4 stalled on store forwarding
  // (a quarter of startVertex's time).
  void setZ(const glm::vec3& n) {
    z = n;
    orthonormalBasis(n, x, y);
  }
  glm::vec3 toLocal(const glm::vec3& v) const { return {dot(v, x), dot(v, y), dot(v, z)}; }
  glm::vec3 toWorld(const glm::vec3& v) const { return v.x * x + v.y * y + v.z * z; }
};

// Concentric map of [0,1)^2 onto the unit disk (Shirley & Chiu, "A Low Distortion Map
// Between Disk and Square", JGT 2(3), 1997); keeps stratification of u.
glm::vec2 sampleUniformDiskConcentric(glm::vec2 u);

// Cosine-weighted hemisphere around +z by Malley's method (pbrt sec. A.5.3).
glm::vec3 sampleCosineHemisphere(glm::vec2 u);
inline float cosineHemispherePdf(float cosTheta) {
  return std::max(0.0f, cosTheta) * kInvPi;
}

// Uniform over the hemisphere around +z (pbrt sec. A.5.2): z = u.x.
glm::vec3 sampleUniformHemisphere(glm::vec2 u);
inline float uniformHemispherePdf() {
  return 0.5f * kInvPi;
}

glm::vec3 sampleUniformSphere(glm::vec2 u);
inline float uniformSpherePdf() {
  return kInv4Pi;
}

// Uniform over the cone of directions within acos(cosThetaMax) of +z (pbrt sec. A.5.4).
glm::vec3 sampleUniformCone(glm::vec2 u, float cosThetaMax);
float uniformConePdf(float cosThetaMax);

// Veach's power heuristic with beta = 2 (Veach, PhD thesis, 1997, eq. 9.13): the weight
// of strategy f that took nf samples against g with ng.
float powerHeuristic(int nf, float fPdf, int ng, float gPdf);

// A piecewise-constant density on [0,1) with n equal cells proportional to |f| (pbrt sec.
// A.5.1). An all-zero f is treated as constant, so sampling always succeeds and every pdf
// it reports is positive.
class Distribution1D {
 public:
  struct Sample {
    float x = 0.0f;    // in [0,1)
    float pdf = 0.0f;  // density w.r.t. x
    int index = 0;     // the cell x lies in
  };
  struct Discrete {
    int index = 0;
    float pmf = 0.0f;
  };

  Distribution1D() = default;
  explicit Distribution1D(std::span<const float> f);

  Sample sampleContinuous(float u) const;
  Discrete sampleDiscrete(float u) const;
  int sampleIndex(float u) const { return findCell(u); }  // sampleDiscrete's index alone
  float pdf(float x) const { return cellPdf(cellIndex(x, size())); }   // density at x in [0,1]
  float cellPdf(int index) const { return func_[index] / integral_; }  // ... in cell 'index'
  float pmf(int index) const { return func_[index] / (integral_ * float(size())); }

  int size() const { return int(func_.size()); }
  float integral() const { return integral_; }  // of the (possibly substituted) f over [0,1]
  float value(int index) const { return func_[index]; }

 private:
  int findCell(float u) const;
  std::vector<float> func_;
  std::vector<float> cdf_;  // size n + 1, cdf_[0] = 0, cdf_[n] = 1
  // Guide table (the cutpoint method; Chen & Asau 1974): with G = guide_.size() - 1, a power
  // of two, guide_[j] is the cell of u = j / G, so the cell of any u in [j / G, (j + 1) / G)
  // lies in [guide_[j], guide_[j + 1]]. A search over the whole cdf is a chain of dependent
  // loads, ~6 per call on the 64-cell sky rows, and an environment sample takes two (the
  // searches were 5.7 % of an atrium bench_trace profile); the guide leaves one or two.
  std::vector<int> guide_;
  float integral_ = 0.0f;
};

// A piecewise-constant density on [0,1)^2 over an nx x ny grid, f[y * nx + x] (pbrt sec.
// A.5.2): a marginal over rows y and one conditional per row.
class Distribution2D {
 public:
  struct Sample {
    glm::vec2 p{0.0f};  // (x, y) in [0,1)^2
    float pdf = 0.0f;   // density w.r.t. dx dy
    glm::ivec2 cell{0};
  };

  Distribution2D() = default;
  Distribution2D(std::span<const float> f, int nx, int ny);

  Sample sample(glm::vec2 u) const;
  float pdf(glm::vec2 p) const;
  bool empty() const { return rows_.empty(); }
  int width() const { return width_; }
  int height() const { return int(rows_.size()); }

 private:
  std::vector<Distribution1D> rows_;
  Distribution1D marginal_;
  // pdf() per cell, row by row: the marginal's density times the row's, as they give it
  // (one load where there were two through rows_, whose tables lie apart in memory: the
  // environment's MIS density is taken for every ray that leaves the scene).
  std::vector<float> cellPdf_;
  int width_ = 0;
};

}  // namespace photovr
