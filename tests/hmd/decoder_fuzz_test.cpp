// Bounded fuzzing of every decoder: random and mutated reports must be accepted or
// rejected with a reason, never crash or trip the sanitizers (the ASan/UBSan build runs
// this too). Fixed seed: a failure reproduces.
#include <random>

#include <gtest/gtest.h>

#include "hmd/feature_reports.h"
#include "hmd/fusion.h"
#include "hmd/sensor_stream.h"
#include "hmd/synthetic.h"

namespace photovr::hmd {
namespace {

// 20000 inputs run in well under a second in Release and a few seconds under ASan.
constexpr int kIterations = 20000;

std::vector<std::vector<uint8_t>> seeds() {
  MotionScript script;
  script.segments = {{0.05, {0.3, -1.0, 0.2}}};
  script.samplesPerReport = 3;
  std::vector<std::vector<uint8_t>> out = toVectors(synthesize(script).reports);
  for (auto b : {encode(ConfigReport{}), encode(RangeReport{}), encode(DisplayInfoReport{}),
                 encode(TrackingLedsReport::blinking()), encode(KeepAliveReport{}),
                 encode(LensDistortionReport::firmwareDefault())})
    out.push_back(b);
  return out;
}

std::vector<uint8_t> mutate(std::vector<uint8_t> b, std::mt19937& rng) {
  std::uniform_int_distribution<int> byte(0, 255), op(0, 4);
  switch (op(rng)) {
    case 0:  // flip bits
      for (int i = 0, n = 1 + rng() % 4; i < n && !b.empty(); ++i)
        b[rng() % b.size()] ^= 1 << (rng() % 8);
      break;
    case 1:
      b.resize(rng() % (b.size() + 1));
      break;  // truncate
    case 2:
      b.resize(b.size() + rng() % 16, uint8_t(byte(rng)));
      break;  // extend
    case 3:   // fully random, random length, plausible ID
      b.assign(rng() % 80, 0);
      for (uint8_t& v : b) v = uint8_t(byte(rng));
      if (!b.empty() && rng() % 2)
        b[0] = std::array<uint8_t, 7>{0x0B, 2, 4, 9, 0x0C, 0x11, 0x16}[rng() % 7];
      break;
    default:  // overwrite a field-sized run
      for (size_t i = rng() % (b.size() + 1), n = 0; i < b.size() && n < 4; ++i, ++n)
        b[i] = uint8_t(byte(rng));
  }
  return b;
}

TEST(DecoderFuzz, RandomAndMutatedReportsAreCountedNeverTrusted) {
  const auto corpus = seeds();
  std::mt19937 rng(20240601);
  SensorStream stream;
  OrientationFilter filter;
  DecodeStats features;
  uint64_t samples = 0;
  for (int i = 0; i < kIterations; ++i) {
    const std::vector<uint8_t> b = mutate(corpus[rng() % corpus.size()], rng);
    for (const ImuSample& s : stream.push(b, i * 1e-3)) {
      // Whatever was accepted is finite and within what the format can carry.
      ASSERT_TRUE(std::isfinite(s.dt) && s.dt >= 0.0 &&
                  s.dt <= 0.254);  // 253 averaged samples at most
      ASSERT_LE(glm::length(s.gyro), 2000.0 * 0.0174533 * 1.1 * 1.8);
      filter.update(s);
      ++samples;
    }
    ASSERT_NEAR(glm::length(filter.orientation()), 1.0, 1e-9);  // finite and normalised
    decodeConfig(b, &features), decodeRange(b, &features), decodeDisplayInfo(b, &features);
    decodeTrackingLeds(b, &features), decodeKeepAlive(b, &features);
    decodeLensDistortion(b, &features);
  }
  const DecodeStats& s = stream.stats();
  EXPECT_EQ(s.accepted + s.rejectedTotal(), uint64_t(kIterations));  // every report counted
  EXPECT_EQ(features.accepted + features.rejectedTotal(), 6u * kIterations);
  EXPECT_GT(s.rejectedTotal(), 0u);
  EXPECT_GT(samples, 0u);
}

}  // namespace
}  // namespace photovr::hmd
