#include "core/perceptual_metrics.h"

#include <cmath>
#include <stdexcept>

#include "core/tonemap.h"

namespace photovr {
namespace {

// The 2-D window is the product of this normalised 1-D Gaussian with itself.
std::vector<double> gaussian1d() {
  std::vector<double> g(kSsimWindow);
  double sum = 0.0;
  for (int i = 0; i < kSsimWindow; ++i) {
    const double d = i - kSsimWindow / 2;
    g[i] = std::exp(-d * d / (2.0 * kSsimSigma * kSsimSigma));
    sum += g[i];
  }
  for (double& v : g) v /= sum;
  return g;
}

// Gaussian-weighted mean of f(x, y) over every 'valid' window (separable: rows, then columns).
template <typename F>
std::vector<double> localMean(F&& f, int w, int h, const std::vector<double>& g) {
  const int vw = w - kSsimWindow + 1, vh = h - kSsimWindow + 1;
  std::vector<double> rows(size_t(vw) * h), out(size_t(vw) * vh, 0.0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < vw; ++x) {
      double s = 0.0;
      for (int k = 0; k < kSsimWindow; ++k) s += g[k] * f(size_t(y) * w + x + k);
      rows[size_t(y) * vw + x] = s;
    }
  for (int y = 0; y < vh; ++y)
    for (int k = 0; k < kSsimWindow; ++k)
      for (int x = 0; x < vw; ++x) out[size_t(y) * vw + x] += g[k] * rows[size_t(y + k) * vw + x];
  return out;
}

}  // namespace

double ssim(const std::vector<float>& x, const std::vector<float>& y, int w, int h) {
  if (w < kSsimWindow || h < kSsimWindow || x.size() != size_t(w) * h || y.size() != x.size())
    throw std::invalid_argument("ssim: images must be equal in size and at least 11 x 11");
  const std::vector<double> g = gaussian1d();
  const auto mx = localMean([&](size_t i) { return double(x[i]); }, w, h, g);
  const auto my = localMean([&](size_t i) { return double(y[i]); }, w, h, g);
  const auto mxx = localMean([&](size_t i) { return double(x[i]) * x[i]; }, w, h, g);
  const auto myy = localMean([&](size_t i) { return double(y[i]) * y[i]; }, w, h, g);
  const auto mxy = localMean([&](size_t i) { return double(x[i]) * y[i]; }, w, h, g);
  const double c1 = kSsimK1 * kSsimK1, c2 = kSsimK2 * kSsimK2;  // eq. 7 and 9 with L = 1
  double sum = 0.0;
  for (size_t i = 0; i < mx.size(); ++i) {
    // Written so that swapping x and y permutes only commutative operands, and x == y gives
    // numerator == denominator bit for bit (2 * (a * a) == a * a + a * a in IEEE arithmetic).
    const double sx = mxx[i] - mx[i] * mx[i], sy = myy[i] - my[i] * my[i];
    const double sxy = mxy[i] - mx[i] * my[i];
    sum += (2.0 * (mx[i] * my[i]) + c1) * (2.0 * sxy + c2) /
           ((mx[i] * mx[i] + my[i] * my[i] + c1) * (sx + sy + c2));  // eq. 13
  }
  return sum / double(mx.size());
}

std::vector<float> displayLuminance(const std::vector<glm::vec3>& linear, float exposure) {
  std::vector<float> luma(linear.size());
  for (size_t i = 0; i < linear.size(); ++i) {
    const glm::vec3 c = glm::vec3(displayColor(linear[i], exposure)) / 255.0f;
    luma[i] = 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b;
  }
  return luma;
}

double ssimDisplay(const std::vector<glm::vec3>& image, const std::vector<glm::vec3>& reference,
                   int width, int height, float exposure) {
  return ssim(displayLuminance(image, exposure), displayLuminance(reference, exposure), width,
              height);
}

}  // namespace photovr
