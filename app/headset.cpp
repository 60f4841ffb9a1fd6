#include "app/headset.h"

#include <algorithm>

#include "core/error.h"
#include "hmd/fusion.h"
#include "hmd/recording.h"
#include "hmd/sensor_stream.h"

namespace photovr::app {
namespace {

// A recording decoded and fused up front: orientation over device time, for headless runs
// that must not depend on how fast the replay is read.
class RecordedTrack final : public hmd::HeadPoseSource {
 public:
  explicit RecordedTrack(const std::string& path) : path_(path) {
    hmd::SensorStream stream;
    hmd::OrientationFilter filter;
    for (const hmd::HidRecord& r : hmd::readRecording(path)) {
      if (r.kind != hmd::HidRecord::Input) continue;
      for (const hmd::ImuSample& s : stream.push(r.bytes, double(r.hostNs) * 1e-9)) {
        filter.update(s);
        keys_.push_back({filter.time(), glm::quat(filter.orientation())});
      }
    }
    if (keys_.empty()) throw InputError(path, "no sensor report in the recording");
    const double t0 = keys_.front().t;
    for (Key& k : keys_) k.t -= t0;
  }
  Pose pose(double t) override {
    auto it = std::upper_bound(keys_.begin(), keys_.end(), t,
                               [](double v, const Key& k) { return v < k.t; });
    Pose p;
    p.orientation = (it == keys_.begin() ? it : it - 1)->q;
    return p;
  }
  std::string status() const override { return "replay " + path_ + " (decoded up front)"; }

 private:
  struct Key {
    double t;
    glm::quat q;
  };
  std::string path_;
  std::vector<Key> keys_;
};

}  // namespace

HmdSpec extractHmdOption(Args& args) {
  HmdSpec spec;
  auto it = std::find(args.begin(), args.end(), "--hmd");
  if (it == args.end()) return spec;
  if (it + 1 == args.end())
    throw UsageError("--hmd: missing value (dk2, replay FILE, sim FILE, none)");
  spec.kind = *(it + 1);
  size_t taken = 2;
  if (spec.kind == "replay" || spec.kind == "sim") {
    if (it + 2 == args.end() || (it + 2)->rfind("--", 0) == 0)
      throw UsageError("--hmd " + spec.kind + ": missing FILE");
    spec.file = *(it + 2);
    taken = 3;
  } else if (spec.kind != "dk2" && spec.kind != "none") {
    throw UsageError("--hmd: '" + spec.kind + "' is not one of dk2, replay FILE, sim FILE, none");
  }
  args.erase(it, it + long(taken));
  if (std::find(args.begin(), args.end(), "--hmd") != args.end())
    throw UsageError("--hmd: given twice");
  return spec;
}

std::unique_ptr<hmd::HeadPoseSource> openHeadPoseSource(const HmdSpec& spec, bool interactive,
                                                        std::string* why) {
  if (spec.kind == "sim") return std::make_unique<hmd::SimHeadset>(hmd::loadPoseScript(spec.file));
  if (spec.kind == "replay") {
    if (!interactive) return std::make_unique<RecordedTrack>(spec.file);
    hmd::readRecording(spec.file);  // malformed files: an InputError here, not in a thread
    auto device =
        std::make_unique<hmd::ReplayDevice>(spec.file, hmd::ReplayDevice::Pacing::Recorded);
    return std::make_unique<hmd::Dk2HeadTracker>(std::move(device));
  }
  if (spec.kind == "dk2") return hmd::openDk2HeadTracker(why);
  return nullptr;
}

}  // namespace photovr::app
