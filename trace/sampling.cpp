#include "trace/sampling.h"

#include <cassert>
#include <limits>

#include "trace/bsdf_lanes.h"

namespace photovr {

glm::vec2 sampleUniformDiskConcentric(glm::vec2 u) {
  glm::vec2 d;
  lanes::concentricDiskOf(u.x, u.y, d.x, d.y);
  return d;
}

glm::vec3 sampleCosineHemisphere(glm::vec2 u) {
  const lanes::V3<float> w = lanes::cosineHemisphereOf(u.x, u.y);
  return {w.x, w.y, w.z};
}

glm::vec3 sampleUniformHemisphere(glm::vec2 u) {
  const float z = u.x;
  const float r = safeSqrt(1.0f - z * z);
  const float phi = 2.0f * kPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

glm::vec3 sampleUniformSphere(glm::vec2 u) {
  const float z = 1.0f - 2.0f * u.x;
  const float r = safeSqrt(1.0f - z * z);
  const float phi = 2.0f * kPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

glm::vec3 sampleUniformCone(glm::vec2 u, float cosThetaMax) {
  const float cosTheta = (1.0f - u.x) + u.x * cosThetaMax;
  const float sinTheta = safeSqrt(1.0f - cosTheta * cosTheta);
  const float phi = 2.0f * kPi * u.y;
  return {sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta};
}

float uniformConePdf(float cosThetaMax) {
  const float solidAngle = 2.0f * kPi * (1.0f - cosThetaMax);
  return solidAngle > 0.0f ? 1.0f / solidAngle : 0.0f;
}

float powerHeuristic(int nf, float fPdf, int ng, float gPdf) {
  const float f = float(nf) * fPdf, g = float(ng) * gPdf;
  if (f == 0.0f) return 0.0f;
  // f^2 overflows for pdfs of near-delta lobes (> 1.8e19); then f dominates (pbrt 4th ed.,
  // sec. 2.2.2, PowerHeuristic).
  if (!isFinite(f * f)) return 1.0f;
  return (f * f) / (f * f + g * g);
}

// ---------------------------------------------------------------------------------------

namespace {

// The guide table's resolution: the largest power of two <= n, up to this many cells
// (1 KiB per row of an environment map; a 2048-wide row then searches 8 cells).
constexpr int kMaxGuideCells = 256;

// The last index in [first, first + len) whose cdf value is <= u, given that the first one
// is (or the first when none is): a binary search without branches. u is random, so a
// compare-and-jump search mispredicts about every other step; each step here keeps the
// half whose first element is still <= u (a conditional move). The predicate !(u < cdf)
// holds on a prefix of the sorted cdf, so the answer is std::upper_bound's minus one.
int lastAtMost(const float* cdf, int first, int len, float u) {
  const float* p = cdf + first;
  size_t n = size_t(len);
  while (n > 1) {
    const size_t half = n / 2;
    p = u < p[half] ? p : p + half;
    n -= half;
  }
  return int(p - cdf);
}

}  // namespace

Distribution1D::Distribution1D(std::span<const float> f) : func_(f.size()), cdf_(f.size() + 1) {
  assert(!f.empty());
  const size_t n = f.size();
  double sum = 0.0;
  for (size_t i = 0; i < n; ++i) {
    // Negative and NaN entries would break the cdf's monotonicity; they count as zero.
    func_[i] = f[i] > 0.0f ? std::min(f[i], std::numeric_limits<float>::max()) : 0.0f;
    sum += func_[i];
  }
  if (sum == 0.0) {
    std::fill(func_.begin(), func_.end(), 1.0f);
    sum = double(n);
  }
  // Accumulate in double: float sums of millions of pixels lose the small cells.
  double running = 0.0;
  cdf_[0] = 0.0f;
  for (size_t i = 0; i < n; ++i) {
    running += func_[i];
    cdf_[i + 1] = float(running / sum);
  }
  cdf_[n] = 1.0f;
  integral_ = float(sum / double(n));
  int g = 1;
  while (2 * g <= int(n) && 2 * g <= kMaxGuideCells) g *= 2;
  guide_.resize(size_t(g) + 1);
  for (int j = 0; j <= g; ++j) {
    const float u = float(j) / float(g);
    guide_[j] = j == g ? int(n) - 1 : lastAtMost(cdf_.data(), 0, int(n) + 1, u);
  }
}

int Distribution1D::findCell(float u) const {
  // The last cell whose cdf start is <= u; cells of zero width are skipped because the
  // search passes over runs of equal cdf values. For u in [0, 1) (every sampler's), cdf_[0]
  // = 0 <= u < cdf_[n] = 1, and the guide bounds the search exactly (it is monotone in u).
  const int g = int(guide_.size()) - 1;
  if (u >= 0.0f && u < 1.0f) {
    const int j = int(u * float(g));  // exact: g is a power of two
    return lastAtMost(cdf_.data(), guide_[j], guide_[j + 1] - guide_[j] + 1, u);
  }
  // NaN or outside [0, 1): std::upper_bound's answer, clamped to the cells.
  const int last = lastAtMost(cdf_.data(), 0, int(cdf_.size()), u);
  const int i = last + (u < cdf_[last] ? 0 : 1) - 1;
  return std::clamp(i, 0, size() - 1);
}

Distribution1D::Sample Distribution1D::sampleContinuous(float u) const {
  const int i = findCell(u);
  float du = u - cdf_[i];
  const float width = cdf_[i + 1] - cdf_[i];
  if (width > 0.0f) du /= width;
  Sample s;
  s.index = i;
  s.x = std::min((float(i) + std::clamp(du, 0.0f, 1.0f)) / float(size()), kOneMinusEpsilon);
  s.pdf = func_[i] / integral_;
  return s;
}

Distribution1D::Discrete Distribution1D::sampleDiscrete(float u) const {
  const int i = findCell(u);
  return {i, pmf(i)};
}

// ---------------------------------------------------------------------------------------

Distribution2D::Distribution2D(std::span<const float> f, int nx, int ny) {
  assert(nx > 0 && ny > 0 && f.size() == size_t(nx) * size_t(ny));
  rows_.reserve(ny);
  std::vector<float> rowIntegrals(ny);
  for (int y = 0; y < ny; ++y) {
    rows_.emplace_back(f.subspan(size_t(y) * nx, nx));
    // A row whose f is all zero was made constant by Distribution1D; its marginal weight
    // must stay zero, so take the integral of the original row.
    double sum = 0.0;
    for (int x = 0; x < nx; ++x) sum += f[size_t(y) * nx + x] > 0.0f ? f[size_t(y) * nx + x] : 0.0f;
    rowIntegrals[y] = float(sum / nx);
  }
  marginal_ = Distribution1D(rowIntegrals);
  width_ = nx;
  cellPdf_.resize(size_t(nx) * size_t(ny));
  for (int y = 0; y < ny; ++y)
    for (int x = 0; x < nx; ++x)
      cellPdf_[size_t(y) * nx + x] = marginal_.cellPdf(y) * rows_[y].cellPdf(x);
}

Distribution2D::Sample Distribution2D::sample(glm::vec2 u) const {
  const Distribution1D::Sample sy = marginal_.sampleContinuous(u.y);
  const Distribution1D::Sample sx = rows_[sy.index].sampleContinuous(u.x);
  return {{sx.x, sy.x}, sx.pdf * sy.pdf, {sx.index, sy.index}};
}

float Distribution2D::pdf(glm::vec2 p) const {
  return cellPdf_[size_t(cellIndex(p.y, height())) * width_ + cellIndex(p.x, width_)];
}

}  // namespace photovr
