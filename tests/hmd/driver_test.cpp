// The DK2 driver through the HmdDevice seam: start-up bytes, keep-alive timer, reader
// thread, shutdown, a vanishing device, and record/replay equivalence.
#include "hmd/dk2_driver.h"

#include <filesystem>
#include <sstream>
#include <thread>

#include <gtest/gtest.h>

#include "core/error.h"
#include "hmd/head_tracker.h"
#include "hmd/recording.h"
#include "hmd/synthetic.h"

namespace photovr::hmd {
namespace {

using Bytes = std::vector<uint8_t>;

SyntheticStream turningStream(double seconds = 0.5) {
  MotionScript script;
  script.segments = {{0.1, {}}, {seconds, {0.2, 1.0, -0.1}}};
  script.gyroNoise = 0.005;
  script.accelNoise = 0.05;
  script.samplesPerReport = 2;
  return synthesize(script);
}

// Waits until the reader has consumed the device (it reports 'lost' at the end).
void waitForEnd(const Dk2Driver& d) {
  for (int i = 0; i < 2000 && !d.lost(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  ASSERT_TRUE(d.lost());
}

std::string tempPath(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("photovr_hmd_" + name)).string();
}

TEST(Dk2Driver, StartUpSendsTheDocumentedSequenceAndShutdownTurnsTheLedsOff) {
  auto device = std::make_unique<SyntheticDevice>(std::vector<Bytes>{},
                                                  SyntheticDevice::Options{.vanishAtEnd = false});
  SyntheticDevice* dev = device.get();
  std::ostringstream log;
  Dk2Driver driver(std::move(device), {.log = &log});
  driver.start();
  driver.stop();
  const std::vector<Bytes> sets = dev->sets();
  ASSERT_EQ(sets.size(), 4u);
  EXPECT_EQ(sets[0], (Bytes{0x11, 0x00, 0x00, 0x0B, 0x10, 0x27}));        // keep-alive first
  EXPECT_EQ(sets[1], (Bytes{0x02, 0x00, 0x00, 0x2C, 0x00, 0xE8, 0x03}));  // 1000 Hz
  EXPECT_EQ(sets[2], encode(TrackingLedsReport::blinking()));
  Bytes off = encode(TrackingLedsReport::blinking());
  off[4] &= ~TrackingLedsReport::kEnable;
  EXPECT_EQ(sets[3], off);
  EXPECT_TRUE(driver.info().lens.has_value());
  EXPECT_EQ(driver.info().display, DisplayInfoReport{});
  EXPECT_EQ(driver.featureStats().rejectedTotal(), 0u);
  EXPECT_EQ(log.str(), "");
}

TEST(Dk2Driver, KeepAliveIsResentOnItsTimer) {
  auto device = std::make_unique<SyntheticDevice>(std::vector<Bytes>{},
                                                  SyntheticDevice::Options{.vanishAtEnd = false});
  SyntheticDevice* dev = device.get();
  Dk2Driver driver(std::move(device),
                   {.keepAlivePeriod = std::chrono::milliseconds(5), .readTimeoutMs = 1});
  driver.start();
  std::this_thread::sleep_for(std::chrono::milliseconds(60));
  driver.stop();
  int keepAlives = 0;
  for (const Bytes& s : dev->sets()) keepAlives += s[0] == KeepAliveReport::kId;
  // 60 ms at a 5 ms period: ~12; a loaded CI machine may stretch sleeps, so ask for 3.
  EXPECT_GE(keepAlives, 3);
}

TEST(Dk2Driver, ReaderDecodesEveryReportAndSkipsCorruptOnes) {
  const SyntheticStream stream = turningStream();
  std::vector<Bytes> reports = toVectors(stream.reports);
  Bytes corrupt = reports[10];
  corrupt[3] = 0;  // no samples
  reports.insert(reports.begin() + 20, corrupt);
  reports.insert(reports.begin() + 30, Bytes{0x0B, 1, 2});  // truncated
  reports.insert(reports.begin() + 40, Bytes(64, 0x01));    // a DK1-format report
  std::ostringstream log;
  Dk2Driver driver(std::make_unique<SyntheticDevice>(reports, SyntheticDevice::Options{}),
                   {.log = &log});
  driver.start();
  waitForEnd(driver);
  const std::vector<ImuSample> samples = driver.takeSamples();
  EXPECT_EQ(samples.size(), 2 * stream.reports.size());
  const DecodeStats stats = driver.sensorStats();
  EXPECT_EQ(stats.accepted, stream.reports.size());
  EXPECT_EQ(stats.rejectedFor(Reject::NoSamples), 1u);
  EXPECT_EQ(stats.rejectedFor(Reject::Short), 1u);
  EXPECT_EQ(stats.rejectedFor(Reject::WrongId), 1u);
}

TEST(Dk2Driver, VanishingDeviceHoldsTheLastPoseAndSaysSoOnce) {
  const SyntheticStream stream = turningStream();
  std::ostringstream log;
  Dk2HeadTracker tracker(std::make_unique<SyntheticDevice>(stream.reports), {.log = &log});
  waitForEnd(tracker.driver());
  const Pose a = tracker.poseAhead(0.02);
  const Pose b = tracker.poseAhead(0.5);
  EXPECT_EQ(a.orientation, b.orientation);  // no extrapolation of a stale rate
  EXPECT_EQ(log.str(),
            "hmd: synthetic DK2: no more sensor reports (device lost or recording "
            "ended); holding the last pose\n");
  EXPECT_NE(tracker.status().find("lost"), std::string::npos);
  // The held pose is where the stream left the head (noise-level tilt/yaw error).
  const double err =
      2.0 * std::acos(std::min(
                1.0, std::abs(glm::dot(glm::dquat(a.orientation), stream.finalOrientation))));
  EXPECT_LT(err, 0.01);
}

TEST(Dk2Driver, RefusedKeepAliveIsAnError) {
  auto device = std::make_unique<SyntheticDevice>(std::vector<Bytes>{},
                                                  SyntheticDevice::Options{.refuseSets = true});
  Dk2Driver driver(std::move(device));
  EXPECT_THROW(driver.start(), InputError);
}

TEST(Dk2Driver, MissingLensReportFallsBackToNothing) {
  std::ostringstream log;
  Dk2Driver driver(std::make_unique<SyntheticDevice>(
                       std::vector<Bytes>{}, SyntheticDevice::Options{.hasLensReport = false}),
                   {.log = &log});
  driver.start();
  EXPECT_FALSE(driver.info().lens.has_value());
}

std::vector<glm::dquat> fusedPoses(std::unique_ptr<HmdDevice> device) {
  std::ostringstream log;
  Dk2Driver driver(std::move(device), {.log = &log});
  driver.start();
  waitForEnd(driver);
  OrientationFilter filter;
  std::vector<glm::dquat> poses;
  for (const ImuSample& s : driver.takeSamples()) {
    filter.update(s);
    poses.push_back(filter.predict(kDk2PredictionSeconds));
  }
  return poses;
}

TEST(Replay, RecordedSyntheticStreamReplaysToTheSamePoses) {
  const SyntheticStream stream = turningStream();
  const std::string path = tempPath("replay.pvrhid");
  const auto live = fusedPoses(
      std::make_unique<RecordingDevice>(std::make_unique<SyntheticDevice>(stream.reports), path));
  const auto replayed = fusedPoses(std::make_unique<ReplayDevice>(path));
  ASSERT_EQ(live.size(), 2 * stream.reports.size());
  ASSERT_EQ(replayed.size(), live.size());
  for (size_t i = 0; i < live.size(); ++i) ASSERT_EQ(live[i], replayed[i]) << i;  // bit-exact

  const std::vector<HidRecord> records = readRecording(path);
  size_t inputs = 0, gets = 0;
  for (const HidRecord& r : records) {
    inputs += r.kind == HidRecord::Input;
    gets += r.kind == HidRecord::FeatureGet;
  }
  EXPECT_EQ(inputs, stream.reports.size());
  EXPECT_EQ(gets, 4u);  // range, display, lens, config (no LED GET: the device vanished)
  std::filesystem::remove(path);
}

TEST(Replay, WriterAndReaderRoundTripAndBadFilesNameTheRecord) {
  const std::string path = tempPath("format.pvrhid");
  const std::vector<HidRecord> records = {
      {HidRecord::FeatureSet, 5, {0x11, 0, 0, 0x0B, 0x10, 0x27}},
      {HidRecord::Input, 1ull << 40, Bytes(64, 0x0B)}};
  {
    RecordingWriter w(path);
    for (const HidRecord& r : records) w.write(r);
  }
  EXPECT_EQ(readRecording(path), records);
  EXPECT_EQ(std::filesystem::file_size(path), 8u + 11 + 6 + 11 + 64);
  std::filesystem::resize_file(path, 8 + 11 + 6 + 11 + 10);  // cut the second report
  try {
    readRecording(path);
    FAIL() << "truncated recording accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), path + ": record 1 at byte 25: truncated report");
  }
  std::filesystem::remove(path);
  EXPECT_THROW(readRecording(path), InputError);
}

TEST(Replay, RecordedPacingWaitsForTheRecordedHostTimes) {
  const std::string path = tempPath("pacing.pvrhid");
  {
    RecordingWriter w(path);
    for (uint64_t ms : {0, 10, 30}) w.write({HidRecord::Input, ms * 1000000, Bytes(64, 0x0B)});
  }
  ReplayDevice replay(path, ReplayDevice::Pacing::Recorded);
  Bytes buffer(64);
  const double start = hostSeconds();
  for (int i = 0; i < 3; ++i) EXPECT_EQ(replay.readReport(buffer, 100), 64);
  EXPECT_GE(hostSeconds() - start, 0.029);  // sleeps only ever overshoot
  EXPECT_EQ(replay.readReport(buffer, 100), -1);
  EXPECT_EQ(replay.getFeature(buffer), -1);  // no GET recorded for 0x0B
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace photovr::hmd
