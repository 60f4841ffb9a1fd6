// Byte-exact parsing of the DK2 sensor report 0x0B (dk2.md §3).
#include "hmd/sensor_report.h"

#include <gtest/gtest.h>

namespace photovr::hmd {
namespace {

std::array<uint8_t, 8> packed(const Packed21& v) {
  std::array<uint8_t, 8> b{};
  pack21(v, b.data());
  return b;
}

// dk2.md §3 test vectors.
TEST(Packed21, MatchesTheReferenceVectors) {
  EXPECT_EQ(packed({0, 0, 98000}), (std::array<uint8_t, 8>{0, 0, 0, 0, 0, 0x02, 0xFD, 0xA0}));
  EXPECT_EQ(packed({-1, 12345, -98000}),
            (std::array<uint8_t, 8>{0xFF, 0xFF, 0xF8, 0x0C, 0x0E, 0x7D, 0x02, 0x60}));
  const uint8_t a[8] = {0xFF, 0xFF, 0xF8, 0x0C, 0x0E, 0x7D, 0x02, 0x60};
  EXPECT_EQ(unpack21(a), (Packed21{-1, 12345, -98000}));
}

TEST(Packed21, RoundTripsTheExtremesAndClampsBeyond) {
  for (Packed21 v : {Packed21{kPacked21Min, kPacked21Max, 0}, Packed21{1, -1, kPacked21Min},
                     Packed21{kPacked21Max, kPacked21Max, kPacked21Max}}) {
    const auto b = packed(v);
    EXPECT_EQ(unpack21(b.data()), v);
  }
  const auto b = packed({kPacked21Max + 5, kPacked21Min - 5, 0});
  EXPECT_EQ(unpack21(b.data()), (Packed21{kPacked21Max, kPacked21Min, 0}));
}

// A report built byte by byte from the table in dk2.md §3, not with the encoder.
ReportBytes handBuiltReport() {
  ReportBytes b{};
  b[0] = 0x0B;
  b[1] = 0x34, b[2] = 0x12;                              // CommandID 0x1234
  b[3] = 5;                                              // NumSamples: slot 0 averages 4
  b[4] = 0xFE, b[5] = 0xFF;                              // SampleCount 65534
  b[6] = 0xAC, b[7] = 0x0D;                              // 3500 -> 35.00 C
  b[8] = 0x78, b[9] = 0x56, b[10] = 0x34, b[11] = 0x12;  // 0x12345678 us
  const auto a0 = packed({0, 98000, 0}), g0 = packed({-1, 12345, -98000});
  const auto a1 = packed({100, 97000, -200}), g1 = packed({0, 0, 98000});
  std::copy(a0.begin(), a0.end(), &b[12]);
  std::copy(g0.begin(), g0.end(), &b[20]);
  std::copy(a1.begin(), a1.end(), &b[28]);
  std::copy(g1.begin(), g1.end(), &b[36]);
  b[44] = 0xD0, b[45] = 0x07;  // mag x 2000 -> 0.2 gauss
  b[46] = 0x30, b[47] = 0xF8;  // mag y -2000
  b[48] = 0xE8, b[49] = 0x03;  // mag z 1000
  b[50] = 7, b[51] = 0;        // FrameCount
  b[52] = 1, b[53] = 2, b[54] = 3, b[55] = 4;
  b[56] = 0x42, b[57] = 3, b[58] = 9, b[59] = 0;
  b[60] = 0xFF, b[61] = 0, b[62] = 0, b[63] = 0x80;
  return b;
}

TEST(SensorReport, DecodesEveryFieldOfAHandBuiltReport) {
  const ReportBytes b = handBuiltReport();
  DecodeStats stats;
  const auto r = decodeSensorReport(b, &stats);
  ASSERT_TRUE(r) << describe(r.reason);
  EXPECT_EQ(r->commandId, 0x1234);
  EXPECT_EQ(r->numSamples, 5);
  EXPECT_EQ(r->slotsUsed(), 2);
  EXPECT_EQ(r->sampleCount, 65534);
  EXPECT_FLOAT_EQ(r->temperatureC(), 35.0f);
  EXPECT_EQ(r->timestampUs, 0x12345678u);
  EXPECT_EQ(r->samples[0].accel, (Packed21{0, 98000, 0}));
  EXPECT_EQ(r->samples[0].gyro, (Packed21{-1, 12345, -98000}));
  EXPECT_EQ(r->samples[1].accel, (Packed21{100, 97000, -200}));
  EXPECT_EQ(r->samples[1].gyro, (Packed21{0, 0, 98000}));
  // Units (dk2.md §3): 1e-4 m/s^2, 1e-4 rad/s, 1e-4 gauss; float rounding only.
  EXPECT_NEAR(accelMps2(r->samples[0]).y, 9.8f, 1e-5f);
  EXPECT_NEAR(gyroRadPerS(r->samples[0]).z, -9.8f, 1e-5f);
  EXPECT_NEAR(r->magGauss().x, 0.2f, 1e-6f);
  EXPECT_NEAR(r->magGauss().y, -0.2f, 1e-6f);
  EXPECT_EQ(r->frameCount, 7);
  EXPECT_EQ(r->frameTimestamp, 0x04030201u);
  EXPECT_EQ(r->frameId, 0x42);
  EXPECT_EQ(r->ledPhase, 3);
  EXPECT_EQ(r->exposureCount, 9);
  EXPECT_EQ(r->exposureTimestamp, 0x800000FFu);
  EXPECT_EQ(stats.accepted, 1u);
  EXPECT_EQ(encodeSensorReport(*r), b);  // byte-exact both ways
}

TEST(SensorReport, SingleSampleReportsLeaveSlotOneZero) {
  SensorReport r;
  r.numSamples = 1;
  r.samples[0].accel = {1, 2, 3};
  const ReportBytes b = encodeSensorReport(r);
  for (int i = 28; i < 44; ++i) EXPECT_EQ(b[i], 0) << i;
  ASSERT_TRUE(decodeSensorReport(b));
  EXPECT_EQ(decodeSensorReport(b)->slotsUsed(), 1);
}

TEST(SensorReport, RejectsTruncatedAndCorruptedReportsWithAReason) {
  DecodeStats stats;
  const ReportBytes good = handBuiltReport();
  EXPECT_EQ(decodeSensorReport({}, &stats).reason, Reject::Empty);
  for (size_t n = 1; n < kSensorReportSize; ++n)
    EXPECT_EQ(decodeSensorReport(std::span(good).first(n), &stats).reason, Reject::Short) << n;

  ReportBytes b = good;
  b[0] = 0x01;  // the DK1 format (dk2.md §2, 0x08 pitfall)
  EXPECT_EQ(decodeSensorReport(b, &stats).reason, Reject::WrongId);
  b = good, b[3] = 0;
  EXPECT_EQ(decodeSensorReport(b, &stats).reason, Reject::NoSamples);
  b = good, b[3] = 1;  // one sample but slot 1 holds data
  EXPECT_EQ(decodeSensorReport(b, &stats).reason, Reject::UnusedSlotNotZero);
  b = good, b[6] = 0xFF, b[7] = 0x7F;  // 327.67 C
  EXPECT_EQ(decodeSensorReport(b, &stats).reason, Reject::OutOfRange);
  b = good;
  const auto wild = packed({kPacked21Max, 0, 0});  // 104.8 rad/s, beyond 2000 deg/s
  std::copy(wild.begin(), wild.end(), &b[20]);
  EXPECT_EQ(decodeSensorReport(b, &stats).reason, Reject::OutOfRange);

  EXPECT_EQ(stats.accepted, 0u);
  EXPECT_EQ(stats.rejectedFor(Reject::Short), kSensorReportSize - 1);
  EXPECT_EQ(stats.rejectedTotal(), kSensorReportSize - 1 + 6);
}

}  // namespace
}  // namespace photovr::hmd
