// Feature reports built byte by byte from dk2.md §2, decoded, re-encoded and corrupted.
#include "hmd/feature_reports.h"

#include <cmath>

#include <gtest/gtest.h>

#include "hmd/lens.h"

namespace photovr::hmd {
namespace {

using Bytes = std::vector<uint8_t>;

TEST(FeatureReports, KeepAliveIsTheDocumentedSixBytes) {
  // dk2.md §2: "Send 11 00 00 0B 10 27".
  EXPECT_EQ(encode(KeepAliveReport{}), (Bytes{0x11, 0x00, 0x00, 0x0B, 0x10, 0x27}));
  const auto r = decodeKeepAlive(Bytes{0x11, 0x00, 0x00, 0x0B, 0x10, 0x27});
  ASSERT_TRUE(r);
  EXPECT_EQ(r->reportId, 0x0B);
  EXPECT_EQ(r->intervalMs, 10000);
}

TEST(FeatureReports, ConfigFirmwareDefaults) {
  const Bytes b{0x02, 0x00, 0x00, 0x2C, 0x00, 0xE8, 0x03};  // flags 0x2C, 1000 Hz
  const auto r = decodeConfig(b);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->flags, ConfigReport::kUseCalibration | ConfigReport::kAutoCalibration |
                          ConfigReport::kCommandKeepAlive);
  EXPECT_EQ(r->packetInterval, 0);
  EXPECT_EQ(r->sampleRate, 1000);
  EXPECT_EQ(encode(*r), b);
}

TEST(FeatureReports, RangeDefaultsAndLimits) {
  const Bytes b{0x04, 0x01, 0x00, 4, 0xD0, 0x07, 0xA0, 0x0F};  // 4 g, 2000 deg/s, 4000 mG
  const auto r = decodeRange(b);
  ASSERT_TRUE(r);
  EXPECT_EQ(*r, RangeReport({1, 4, 2000, 4000}));
  EXPECT_EQ(encode(*r), b);
  Bytes bad = b;
  bad[3] = 3;  // accel range must be 2/4/8/16 g
  EXPECT_EQ(decodeRange(bad).reason, Reject::OutOfRange);
  bad = b, bad[4] = 0x10, bad[5] = 0x27;  // 10000 deg/s
  EXPECT_EQ(decodeRange(bad).reason, Reject::OutOfRange);
}

TEST(FeatureReports, DisplayInfoDk2Defaults) {
  Bytes b(56, 0);
  b[0] = 0x09, b[3] = 1;
  b[4] = 0x80, b[5] = 0x07;  // 1920
  b[6] = 0x38, b[7] = 0x04;  // 1080
  const uint32_t um[6] = {125760, 70740, 35370, 63500, 39620, 39620};
  for (int i = 0; i < 6; ++i)
    for (int k = 0; k < 4; ++k) b[8 + 4 * i + k] = uint8_t(um[i] >> (8 * k));
  const auto r = decodeDisplayInfo(b);
  ASSERT_TRUE(r);
  EXPECT_EQ(*r, DisplayInfoReport{});  // the struct's defaults are dk2.md §2's
  EXPECT_EQ(encode(*r), b);
  Bytes bad = b;
  bad[4] = bad[5] = 0;  // no pixels
  EXPECT_EQ(decodeDisplayInfo(bad).reason, Reject::OutOfRange);
  bad = b, bad[35] = 0x7F, bad[34] = 0xC0;  // first float = NaN
  EXPECT_EQ(decodeDisplayInfo(bad).reason, Reject::OutOfRange);
}

TEST(FeatureReports, TrackingLedsBlinkingAndOff) {
  const Bytes b{0x0C, 0, 0, 0, 0x07, 0, 0x5E, 0x01, 0x1A, 0x41, 0, 0, 0x7F};
  EXPECT_EQ(encode(TrackingLedsReport::blinking()), b);  // 350 us, 16666 us, duty 0x7F
  const auto r = decodeTrackingLeds(b);
  ASSERT_TRUE(r);
  EXPECT_EQ(*r, TrackingLedsReport::blinking());
  Bytes bad = b;
  bad[5] = 0x80;  // undefined flag bit
  EXPECT_EQ(decodeTrackingLeds(bad).reason, Reject::OutOfRange);
}

Bytes firmwareLensBytes() {
  Bytes b(64, 0);
  b[0] = 0x16, b[3] = 1, b[4] = 0, b[8] = 1;  // one entry, index 0, CatmullRom10
  b[10] = 0x68, b[11] = 0x42;                 // 17000 um
  const uint16_t k[11] = {16433, 16712, 17072, 17465, 17924, 18448,
                          19038, 19710, 20480, 21463, 22610};  // round(K * 2^14)
  for (int i = 0; i < 11; ++i) b[12 + 2 * i] = uint8_t(k[i]), b[13 + 2 * i] = uint8_t(k[i] >> 8);
  b[34] = 0x00, b[35] = 0x40;  // MaxR 1.0
  b[36] = 0xBA, b[37] = 0x49;  // 18874 = round(0.036 * 2^19)
  const uint16_t ca[4] = {0x8000 - 7864, 0x8000 - 10486, 0x8000 + 13107, 0x8000 + 10486};
  for (int i = 0; i < 4; ++i) b[38 + 2 * i] = uint8_t(ca[i]), b[39 + 2 * i] = uint8_t(ca[i] >> 8);
  return b;
}

TEST(FeatureReports, LensDistortionFirmwareDefaultDecodesToTheDocumentedModel) {
  const Bytes b = firmwareLensBytes();
  EXPECT_EQ(encode(LensDistortionReport::firmwareDefault()), b);
  const auto r = decodeLensDistortion(b);
  ASSERT_TRUE(r) << describe(r.reason);
  const LensDistortion lens = LensDistortion::fromReport(*r);
  const LensDistortion ref = LensDistortion::dk2Default(0.018);
  // Fixed point: K in 2^-14 (half a step: 3.1e-5), M and CA in 2^-19 (9.6e-7).
  for (int i = 0; i < 11; ++i) EXPECT_NEAR(lens.k[i], ref.k[i], 3.1e-5) << i;
  EXPECT_DOUBLE_EQ(lens.maxR, 1.0);
  EXPECT_NEAR(lens.metresPerTanAngle, 0.036, 9.6e-7);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(lens.chroma[i], ref.chroma[i], 9.6e-7) << i;
  EXPECT_NEAR(lens.eyeReliefM, 0.017, 1e-12);
}

TEST(FeatureReports, LensDistortionRejectsWhatTheInverseCannotUse) {
  Bytes bad = firmwareLensBytes();
  bad[8] = 2;
  EXPECT_EQ(decodeLensDistortion(bad).reason, Reject::UnsupportedVersion);
  bad = firmwareLensBytes(), bad[14] = 0, bad[15] = 0;  // K[1] = 0: not increasing
  EXPECT_EQ(decodeLensDistortion(bad).reason, Reject::OutOfRange);
  bad = firmwareLensBytes(), bad[34] = bad[35] = 0;  // MaxR 0
  EXPECT_EQ(decodeLensDistortion(bad).reason, Reject::OutOfRange);
}

TEST(FeatureReports, EveryDecoderRejectsShortEmptyAndForeignReports) {
  DecodeStats stats;
  const std::vector<Bytes> good = {
      encode(ConfigReport{}),      encode(RangeReport{}),
      encode(DisplayInfoReport{}), encode(TrackingLedsReport{}),
      encode(KeepAliveReport{}),   encode(LensDistortionReport::firmwareDefault())};
  auto reason = [&](size_t kind, std::span<const uint8_t> b) {
    switch (kind) {
      case 0:
        return decodeConfig(b, &stats).reason;
      case 1:
        return decodeRange(b, &stats).reason;
      case 2:
        return decodeDisplayInfo(b, &stats).reason;
      case 3:
        return decodeTrackingLeds(b, &stats).reason;
      case 4:
        return decodeKeepAlive(b, &stats).reason;
      default:
        return decodeLensDistortion(b, &stats).reason;
    }
  };
  for (size_t k = 0; k < good.size(); ++k) {
    EXPECT_EQ(reason(k, good[k]), Reject::None) << k;
    EXPECT_EQ(reason(k, {}), Reject::Empty) << k;
    for (size_t n = 1; n < good[k].size(); ++n)
      EXPECT_EQ(reason(k, std::span(good[k]).first(n)), Reject::Short) << k << " " << n;
    EXPECT_EQ(reason(k, good[(k + 1) % good.size()]), Reject::WrongId) << k;
    Bytes padded = good[k];
    padded.resize(64, 0xEE);  // hidraw may hand back a padded buffer
    EXPECT_EQ(reason(k, padded), Reject::None) << k;
  }
  EXPECT_EQ(stats.accepted, 2 * good.size());
  EXPECT_EQ(stats.rejectedFor(Reject::WrongId), good.size());
}

}  // namespace
}  // namespace photovr::hmd
