#include "tests/trace/chi_square.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

namespace photovr::test {
namespace {

double gammaPrefactor(double a, double x) {
  return std::exp(-x + a * std::log(x) - std::lgamma(a));
}

// P(a, x) by its series (Numerical Recipes, eq. 6.2.5); converges fast for x < a + 1.
double gammaPSeries(double a, double x) {
  double ap = a, del = 1.0 / a, sum = del;
  for (int n = 0; n < 1000 && std::abs(del) > std::abs(sum) * 1e-15; ++n) {
    ap += 1.0;
    del *= x / ap;
    sum += del;
  }
  return sum * gammaPrefactor(a, x);
}

// Q(a, x) by its continued fraction, modified Lentz (Numerical Recipes, eq. 6.2.7).
double gammaQFraction(double a, double x) {
  constexpr double kTiny = 1e-300;
  double b = x + 1.0 - a, c = 1.0 / kTiny, d = 1.0 / b, h = d;
  for (int i = 1; i < 1000; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < kTiny) d = kTiny;
    c = b + an / c;
    if (std::abs(c) < kTiny) c = kTiny;
    d = 1.0 / d;
    const double del = d * c;
    h *= del;
    if (std::abs(del - 1.0) < 1e-15) break;
  }
  return gammaPrefactor(a, x) * h;
}

struct Panel {
  double a, b, fa, fm, fb, whole;
};

double simpson(double a, double b, double fa, double fm, double fb) {
  return (b - a) / 6.0 * (fa + 4.0 * fm + fb);
}

double adaptive(const std::function<double(double)>& f, const Panel& p, double eps, int depth,
                int minDepth) {
  const double m = 0.5 * (p.a + p.b);
  const double flm = f(0.5 * (p.a + m)), frm = f(0.5 * (m + p.b));
  const double left = simpson(p.a, m, p.fa, flm, p.fm);
  const double right = simpson(m, p.b, p.fm, frm, p.fb);
  const double delta = left + right - p.whole;
  // Richardson: the error of the refined estimate is ~delta / 15 (Lyness 1969).
  if (depth <= 0 || (minDepth <= 0 && std::abs(delta) <= 15.0 * eps))
    return left + right + delta / 15.0;
  return adaptive(f, {p.a, m, p.fa, flm, p.fm, left}, 0.5 * eps, depth - 1, minDepth - 1) +
         adaptive(f, {m, p.b, p.fm, frm, p.fb, right}, 0.5 * eps, depth - 1, minDepth - 1);
}

}  // namespace

double regularizedGammaQ(double a, double x) {
  if (x <= 0.0) return 1.0;
  if (x < a + 1.0) return 1.0 - gammaPSeries(a, x);
  return gammaQFraction(a, x);
}

double integrate1D(const std::function<double(double)>& f, double a, double b, double eps,
                   int minDepth, int maxDepth) {
  const double fa = f(a), fm = f(0.5 * (a + b)), fb = f(b);
  return adaptive(f, {a, b, fa, fm, fb, simpson(a, b, fa, fm, fb)}, eps, maxDepth, minDepth);
}

double integrate2D(const std::function<double(double, double)>& f, double x0, double x1, double y0,
                   double y1, double eps, int minDepth, int maxDepth) {
  const double innerEps = eps / (x1 - x0);
  const auto inner = [&](double x) {
    return integrate1D([&](double y) { return f(x, y); }, y0, y1, innerEps, minDepth, maxDepth);
  };
  return integrate1D(inner, x0, x1, eps, minDepth, maxDepth);
}

void Histogram::add(glm::vec2 p) {
  const int x = std::clamp(int(p.x * nx_), 0, nx_ - 1);
  const int y = std::clamp(int(p.y * ny_), 0, ny_ - 1);
  counts_[size_t(y) * nx_ + x] += 1.0;
}

double Histogram::total() const {
  return std::accumulate(counts_.begin(), counts_.end(), failures_);
}

std::string ChiSquareResult::describe() const {
  std::ostringstream s;
  if (!error.empty()) s << error << "; ";
  s << "chi2 = " << statistic << ", dof = " << dof << ", p = " << pValue << " (reject below "
    << kChiSquareAlpha << ")";
  return s.str();
}

ChiSquareResult chiSquareTest(const Histogram& h,
                              const std::function<double(double, double)>& density) {
  const double n = h.total();
  const int cells = h.nx() * h.ny();
  std::vector<double> expected, observed;
  double mass = 0.0;
  for (int y = 0; y < h.ny(); ++y) {
    for (int x = 0; x < h.nx(); ++x) {
      const double p = integrate2D(density, double(x) / h.nx(), double(x + 1) / h.nx(),
                                   double(y) / h.ny(), double(y + 1) / h.ny(), 1e-4 / cells);
      mass += p;
      expected.push_back(p * n);
      observed.push_back(h.count(x, y));
    }
  }
  expected.push_back(std::max(0.0, 1.0 - mass) * n);
  observed.push_back(h.failures());

  // Pool the smallest cells together (pbrt-v4 bsdfs_test.cpp, chi2test).
  std::vector<size_t> order(expected.size());
  std::iota(order.begin(), order.end(), size_t(0));
  std::sort(order.begin(), order.end(),
            [&](size_t a, size_t b) { return expected[a] < expected[b]; });
  ChiSquareResult r;
  double pooledExp = 0.0, pooledObs = 0.0;
  for (size_t i : order) {
    // Quadrature may round a sliver of density to zero; a few samples there are no proof.
    if (expected[i] == 0.0) {
      if (observed[i] > n * 1e-5) {
        r.error = std::to_string(int(observed[i])) + " samples in a cell of expected count 0";
        return r;
      }
    } else if (expected[i] < kMinExpectedCount ||
               (pooledExp > 0.0 && pooledExp < kMinExpectedCount)) {
      pooledExp += expected[i];
      pooledObs += observed[i];
    } else {
      r.statistic += (observed[i] - expected[i]) * (observed[i] - expected[i]) / expected[i];
      ++r.dof;
    }
  }
  if (pooledExp > 0.0) {
    r.statistic += (pooledObs - pooledExp) * (pooledObs - pooledExp) / pooledExp;
    ++r.dof;
  }
  --r.dof;  // the counts sum to n
  if (r.dof < 1) {
    r.error = "grid too coarse: fewer than 2 bins after pooling";
    return r;
  }
  r.pValue = chiSquarePValue(r.statistic, r.dof);
  return r;
}

}  // namespace photovr::test
