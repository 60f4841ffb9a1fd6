// Timing of decoded samples: averaged slots, timestamp wrap, dropped packets (dk2.md §3).
#include "hmd/sensor_stream.h"

#include <gtest/gtest.h>

#include "hmd/synthetic.h"

namespace photovr::hmd {
namespace {

SensorReport report(uint32_t timestampUs, uint8_t n, uint16_t sampleCount) {
  SensorReport r;
  r.timestampUs = timestampUs;
  r.numSamples = n;
  r.sampleCount = sampleCount;
  r.samples[0].gyro = {10000, 0, 0};  // 1 rad/s
  if (n > 1) r.samples[1].gyro = {20000, 0, 0};
  return r;
}

TEST(SensorStream, AveragedSlotStandsForAllButTheNewestSample) {
  SensorStream s;
  s.push(encodeSensorReport(report(1000, 1, 0)));
  const auto out = s.push(encodeSensorReport(report(6000, 5, 1)));  // 5 samples in 5 ms
  ASSERT_EQ(out.size(), 2u);
  EXPECT_NEAR(out[0].dt, 0.004, 1e-12);  // 4 averaged samples
  EXPECT_NEAR(out[1].dt, 0.001, 1e-12);
  EXPECT_NEAR(out[1].time, 0.006, 1e-12);
  EXPECT_NEAR(out[0].time, 0.005, 1e-12);
  EXPECT_FLOAT_EQ(out[0].gyro.x, 1.0f);
  EXPECT_FLOAT_EQ(out[1].gyro.x, 2.0f);
}

TEST(SensorStream, FirstReportUsesTheNominalPeriod) {
  SensorStream s;
  const auto out = s.push(encodeSensorReport(report(123456, 3, 0)));
  ASSERT_EQ(out.size(), 2u);
  EXPECT_NEAR(out[0].dt, 0.002, 1e-12);  // LibOVR 0.3: (n - 1) ms for the averaged slot
}

TEST(SensorStream, TimestampWrapKeepsTimeMonotonic) {
  SensorStream s;
  s.push(encodeSensorReport(report(0xFFFFFC18u, 1, 0)));                   // 2^32 - 1000 us
  const auto out = s.push(encodeSensorReport(report(0x000003E8u, 2, 1)));  // +2000 us
  ASSERT_EQ(out.size(), 2u);
  EXPECT_NEAR(out[1].time - 4294.966296, 0.002, 1e-9);
  EXPECT_NEAR(out[0].dt, 0.001, 1e-12);
  EXPECT_EQ(s.stats().rejectedTotal(), 0u);
}

TEST(SensorStream, BackwardsAndDuplicateReportsAreRejected) {
  SensorStream s;
  const auto a = encodeSensorReport(report(50000, 1, 10));
  s.push(a);
  EXPECT_TRUE(s.push(a).empty());
  EXPECT_TRUE(s.push(encodeSensorReport(report(40000, 1, 11))).empty());
  EXPECT_EQ(s.stats().rejectedFor(Reject::Duplicate), 1u);
  EXPECT_EQ(s.stats().rejectedFor(Reject::TimestampBackwards), 1u);
  EXPECT_EQ(s.push(encodeSensorReport(report(51000, 1, 11))).size(), 1u);  // stream resumes
}

TEST(SensorStream, DroppedPacketsAreCountedAndShortGapsBridged) {
  SensorStream s;
  s.push(encodeSensorReport(report(1000, 1, 0)));
  const auto bridged = s.push(encodeSensorReport(report(9000, 1, 8)));  // 7 samples lost
  ASSERT_EQ(bridged.size(), 1u);
  EXPECT_NEAR(bridged[0].dt, 0.008, 1e-12);
  EXPECT_EQ(s.stats().droppedSamples, 7u);
  const auto resync = s.push(encodeSensorReport(report(509000, 1, 508)));  // 0.5 s gap
  ASSERT_EQ(resync.size(), 1u);
  EXPECT_NEAR(resync[0].dt, kImuPeriod, 1e-12);  // not integrated across the gap
  EXPECT_EQ(s.stats().resyncs, 1u);
  EXPECT_EQ(s.stats().droppedSamples, 7u + 499u);
}

TEST(SensorStream, SampleCountWrapIsNotALoss) {
  SensorStream s;
  s.push(encodeSensorReport(report(1000, 2, 65534)));
  s.push(encodeSensorReport(report(3000, 2, 0)));
  EXPECT_EQ(s.stats().droppedSamples, 0u);
}

}  // namespace
}  // namespace photovr::hmd
