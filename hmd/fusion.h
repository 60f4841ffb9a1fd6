// Orientation from the DK2's IMU: exact per-sample gyro integration, complementary gravity
// tilt correction, gyro-bias estimation while still, and prediction to a display time.
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "hmd/sensor_stream.h"

namespace photovr::hmd {

// DK2 prediction target: mid-scan-out, ~20.9 ms after the newest sample (dk2.md §4).
constexpr double kDk2PredictionSeconds = 0.0209;

struct FusionSettings {
  double gravity = 9.81;  // m/s^2
  // Accel is trusted as gravity only while | |a| - g | is below this: a head accelerating
  // at 1 m/s^2 tilts the apparent vertical by ~6 deg, so stronger pushes are ignored.
  // OpenHMD gates at 0.8 (dk2.md §4); 1.0 keeps correcting through gentle motion.
  double accelGate = 1.0;
  // Complementary-filter time constants (fraction dt / tau of the tilt error removed per
  // sample). Moving: 2 s, long against head accelerations (mostly < 0.5 s and mean-free),
  // short against gyro drift (~0.01 rad/s bias -> < 1.2 deg of tilt error at equilibrium).
  // Still: 0.2 s, so a wrong tilt (start-up, after a resync) is gone within ~1 s: 30 deg
  // decays to 0.5 deg in 0.2 s * ln(60) = 0.82 s. LibOVR 0.3's 0.25 dt gain is tau = 4 s plus
  // a snap on large errors (dk2.md §4); two constants avoid the snap's visible jump.
  double movingTiltTau = 2.0;
  double stillTiltTau = 0.2;
  // Still: |gyro - bias| below 0.05 rad/s (2.9 deg/s, above the DK2's noise) and
  // | |a| - g | below 0.3 m/s^2, for stillHold seconds. A slower deliberate turn held that
  // long is partly learned as bias — the price of a gyro-only yaw (no magnetometer, §4).
  double stillGyro = 0.05;
  double stillAccel = 0.3;
  double stillHold = 0.5;
  // Bias: running mean over the first biasTau seconds of stillness, then an exponential
  // average with that time constant (noise 0.005 rad/s per sample -> ~1e-4 rad/s error).
  double biasTau = 1.0;
  // With no prior orientation the first trusted accel sample sets the tilt directly.
  bool alignOnFirstSample = true;
  double maxPrediction = 0.1;  // s; beyond that extrapolating the rate is a guess
};

// q <- q * rotation by |w| dt about w (body frame): exact for a rate constant over dt.
glm::dquat integrateGyro(const glm::dquat& q, const glm::dvec3& omegaBody, double dt);
// World-frame rotation turning the measured up (q * accel) toward +Y by 'fraction' of the
// angle between them; a rotation about a horizontal axis, so yaw is untouched.
glm::dquat tiltCorrection(const glm::dquat& q, const glm::dvec3& accelBody, double fraction);
// The angle between the measured up and world +Y, radians.
double tiltError(const glm::dquat& q, const glm::dvec3& accelBody);

class OrientationFilter {
 public:
  explicit OrientationFilter(FusionSettings s = {}) : settings_(s) {}
  void update(const ImuSample& s);
  glm::dquat orientation() const { return q_; }  // body -> world (camera convention)
  void setOrientation(const glm::dquat& q) { q_ = q, aligned_ = true; }
  glm::dvec3 gyroBias() const { return bias_; }
  glm::dvec3 angularVelocity() const { return omega_; }  // body frame, bias removed
  bool still() const { return stillTime_ >= settings_.stillHold; }
  double time() const { return time_; }  // of the newest sample, device clock
  bool started() const { return started_; }
  // Orientation 'ahead' seconds after the newest sample, holding the current rate.
  glm::dquat predict(double ahead) const;

 private:
  void updateStillness(const glm::dvec3& gyro, const glm::dvec3& accel, double dt);
  void updateBias(const glm::dvec3& gyro, double dt);
  void correctTilt(const glm::dvec3& accel, double dt);

  FusionSettings settings_;
  glm::dquat q_{1.0, 0.0, 0.0, 0.0};
  glm::dvec3 bias_{0.0}, omega_{0.0};
  double stillTime_ = 0.0, biasLearned_ = 0.0, time_ = 0.0;
  bool aligned_ = false, started_ = false;
};

}  // namespace photovr::hmd
