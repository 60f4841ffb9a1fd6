// Where the head is: one interface for the app and the compositor, with the DK2 (fused
// IMU, predicted to the display time) and the scripted 'sim' headset behind it. The
// desktop camera (desktop_camera.h) is a pure state machine; DesktopHeadset holds one.
#pragma once

#include <memory>
#include <string>

#include "core/camera.h"
#include "hmd/desktop_camera.h"
#include "hmd/dk2_driver.h"
#include "hmd/fusion.h"
#include "hmd/pose_script.h"

namespace photovr::hmd {

class HeadPoseSource {
 public:
  virtual ~HeadPoseSource() = default;
  // The head pose expected at 'displayTime' (seconds; the clock each source documents).
  virtual Pose pose(double displayTime) = 0;
  virtual std::string status() const = 0;  // one line for the overlay
};

// The DK2: orientation only (no positional tracking; position stays at the origin, the
// app adds its base pose). displayTime is on the driver's host clock (hostSeconds()).
class Dk2HeadTracker final : public HeadPoseSource {
 public:
  Dk2HeadTracker(std::unique_ptr<HmdDevice> device, Dk2DriverOptions driverOptions = {},
                 FusionSettings fusion = {});
  Pose pose(double displayTime) override;
  // Fuses the queued samples and predicts 'ahead' seconds past the newest one.
  Pose poseAhead(double ahead);
  std::string status() const override;
  const Dk2Driver& driver() const { return driver_; }
  const OrientationFilter& filter() const { return filter_; }

 private:
  void drain();
  Dk2Driver driver_;
  OrientationFilter filter_;
  double newestHostTime_ = 0.0;
};

// Opens the DK2 over hidapi and starts it; nullptr with 'why' when there is none.
std::unique_ptr<Dk2HeadTracker> openDk2HeadTracker(std::string* why = nullptr);

// Follows a pose script; displayTime is seconds since the script's start.
class SimHeadset final : public HeadPoseSource {
 public:
  explicit SimHeadset(PoseScript script) : script_(std::move(script)) {}
  Pose pose(double displayTime) override { return script_.sample(displayTime); }
  std::string status() const override { return "sim " + script_.source; }
  const PoseScript& script() const { return script_; }

 private:
  PoseScript script_;
};

// The mouse + keys camera for a plain window; the app feeds it its events.
class DesktopHeadset final : public HeadPoseSource {
 public:
  explicit DesktopHeadset(DesktopCamera start = {}, DesktopSettings settings = {})
      : camera_(start), settings_(settings) {}
  void handle(const DesktopInput& input) { camera_ = step(camera_, input, settings_); }
  Pose pose(double) override { return camera_.pose(); }
  std::string status() const override { return "desktop (mouse + WASD, E/Q up/down)"; }
  const DesktopCamera& camera() const { return camera_; }

 private:
  DesktopCamera camera_;
  DesktopSettings settings_;
};

}  // namespace photovr::hmd
