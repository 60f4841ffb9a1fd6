// Chi-square goodness-of-fit testing of sampling routines against their pdfs, after
// pbrt-v4's bsdfs_test.cpp (itself after Wenzel Jakob's Mitsuba tests): histogram the
// samples over a grid, integrate the pdf over every cell for the expected counts, pool
// cells with expected counts below 5, and reject at significance 0.01, Bonferroni-corrected
// over all the chi-square tests of photovr_trace_tests.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace photovr::test {

// The number of chi-square tests in the executable (update when adding one) and the
// per-test significance that keeps the chance of any false alarm across all of them at
// 0.01 (Bonferroni).
inline constexpr int kChiSquareTests = 61;
inline constexpr double kChiSquareAlpha = 0.01 / kChiSquareTests;

// The classic rule of thumb (Cochran 1954): the chi-square approximation of the multinomial
// needs expected counts >= 5 per bin; smaller cells are pooled.
inline constexpr double kMinExpectedCount = 5.0;

// Regularized upper incomplete gamma Q(a, x) = 1 - P(a, x), by its series for x < a + 1
// and by Lentz's continued fraction otherwise (Press et al., "Numerical Recipes", 3rd ed.,
// sec. 6.2).
double regularizedGammaQ(double a, double x);

// P(X >= statistic) for X chi-square distributed with dof degrees of freedom.
inline double chiSquarePValue(double statistic, int dof) {
  return regularizedGammaQ(0.5 * dof, 0.5 * statistic);
}

// Adaptive Simpson quadrature of f over [a, b] to absolute error ~eps. At least 2^minDepth
// panels, so a peak narrower than the interval is not missed by the first five points.
double integrate1D(const std::function<double(double)>& f, double a, double b, double eps,
                   int minDepth = 2, int maxDepth = 14);
// Nested adaptive Simpson over [x0, x1] x [y0, y1].
double integrate2D(const std::function<double(double, double)>& f, double x0, double x1, double y0,
                   double y1, double eps, int minDepth = 2, int maxDepth = 12);

// Counts of samples over an nx x ny grid on [0,1]^2 plus one bin for samples that failed
// (a sampler's "no sample", e.g. a reflection below the surface).
class Histogram {
 public:
  Histogram(int nx, int ny) : nx_(nx), ny_(ny), counts_(size_t(nx) * ny, 0.0) {}
  void add(glm::vec2 p);
  void addFailure() { failures_ += 1.0; }
  int nx() const { return nx_; }
  int ny() const { return ny_; }
  double count(int x, int y) const { return counts_[size_t(y) * nx_ + x]; }
  double failures() const { return failures_; }
  double total() const;

 private:
  int nx_, ny_;
  std::vector<double> counts_;
  double failures_ = 0.0;
};

struct ChiSquareResult {
  double statistic = 0.0;
  int dof = 0;
  double pValue = 0.0;
  std::string error;  // non-empty when the test cannot be made (or fails outright)
  bool passed() const { return error.empty() && pValue >= kChiSquareAlpha; }
  std::string describe() const;
};

// Tests the histogram against `density` on [0,1]^2 (w.r.t. dx dy, with the grid's own
// coordinates); its integral may be below 1, the rest being the probability of failure.
// Cell integrals are computed to an absolute error of 1e-4 / cells of the total, so
// quadrature error adds < 1e-8 N to the statistic: negligible for N <= 1e7.
ChiSquareResult chiSquareTest(const Histogram& h,
                              const std::function<double(double, double)>& density);

}  // namespace photovr::test
