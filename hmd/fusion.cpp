#include "hmd/fusion.h"

#include <algorithm>
#include <cmath>

namespace photovr::hmd {
namespace {

constexpr glm::dvec3 kUp(0.0, 1.0, 0.0);  // at rest the accelerometer reads +g on Y (§3)

}  // namespace

glm::dquat integrateGyro(const glm::dquat& q, const glm::dvec3& w, double dt) {
  const double rate = glm::length(w);
  if (rate * dt < 1e-15) return q;
  return glm::normalize(q * glm::angleAxis(rate * dt, w / rate));
}

double tiltError(const glm::dquat& q, const glm::dvec3& accelBody) {
  const glm::dvec3 up = q * accelBody;
  return std::atan2(glm::length(glm::cross(up, kUp)), glm::dot(up, kUp));
}

glm::dquat tiltCorrection(const glm::dquat& q, const glm::dvec3& accelBody, double fraction) {
  const glm::dvec3 up = glm::normalize(q * accelBody);
  const glm::dvec3 axis = glm::cross(up, kUp);
  const double s = glm::length(axis);
  if (s < 1e-12) return q;  // already level, or upside down (any axis; wait for motion)
  const double angle = std::atan2(s, glm::dot(up, kUp));
  return glm::normalize(glm::angleAxis(angle * fraction, axis / s) * q);
}

void OrientationFilter::updateStillness(const glm::dvec3& gyro, const glm::dvec3& accel,
                                        double dt) {
  const bool quiet = glm::length(gyro - bias_) < settings_.stillGyro &&
                     std::abs(glm::length(accel) - settings_.gravity) < settings_.stillAccel;
  stillTime_ = quiet ? stillTime_ + dt : 0.0;
}

void OrientationFilter::updateBias(const glm::dvec3& gyro, double dt) {
  if (!still() || dt <= 0.0) return;
  biasLearned_ += dt;
  const double k = std::min(1.0, dt / std::min(settings_.biasTau, biasLearned_));
  bias_ += (gyro - bias_) * k;
}

void OrientationFilter::correctTilt(const glm::dvec3& accel, double dt) {
  if (std::abs(glm::length(accel) - settings_.gravity) >= settings_.accelGate) return;
  if (!aligned_) {
    q_ = tiltCorrection(q_, accel, 1.0);
    aligned_ = true;
    return;
  }
  const double tau = still() ? settings_.stillTiltTau : settings_.movingTiltTau;
  q_ = tiltCorrection(q_, accel, std::min(1.0, dt / tau));
}

void OrientationFilter::update(const ImuSample& s) {
  const glm::dvec3 gyro(s.gyro), accel(s.accel);
  if (!settings_.alignOnFirstSample) aligned_ = true;
  updateStillness(gyro, accel, s.dt);
  updateBias(gyro, s.dt);
  omega_ = gyro - bias_;
  q_ = integrateGyro(q_, omega_, s.dt);
  correctTilt(accel, s.dt);
  time_ = s.time;
  started_ = true;
}

glm::dquat OrientationFilter::predict(double ahead) const {
  return integrateGyro(q_, omega_, std::clamp(ahead, 0.0, settings_.maxPrediction));
}

}  // namespace photovr::hmd
