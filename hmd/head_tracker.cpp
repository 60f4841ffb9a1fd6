#include "hmd/head_tracker.h"

namespace photovr::hmd {

Dk2HeadTracker::Dk2HeadTracker(std::unique_ptr<HmdDevice> device, Dk2DriverOptions options,
                               FusionSettings fusion)
    : driver_(std::move(device), std::move(options)), filter_(fusion) {
  driver_.start();
}

void Dk2HeadTracker::drain() {
  for (const ImuSample& s : driver_.takeSamples()) {
    filter_.update(s);
    newestHostTime_ = s.hostTime;
  }
}

Pose Dk2HeadTracker::poseAhead(double ahead) {
  drain();
  Pose p;
  // A lost device holds its last orientation rather than extrapolating a stale rate.
  p.orientation = glm::quat(driver_.lost() ? filter_.orientation() : filter_.predict(ahead));
  return p;
}

Pose Dk2HeadTracker::pose(double displayTime) {
  drain();
  return poseAhead(displayTime - newestHostTime_);
}

std::string Dk2HeadTracker::status() const {
  if (driver_.lost()) return driver_.name() + ": lost, holding the last pose";
  return driver_.name() + (filter_.still() ? ": still" : ": tracking");
}

std::unique_ptr<Dk2HeadTracker> openDk2HeadTracker(std::string* why) {
  std::unique_ptr<HmdDevice> device = openDk2Hid(why);
  if (!device) return nullptr;
  return std::make_unique<Dk2HeadTracker>(std::move(device));
}

}  // namespace photovr::hmd
