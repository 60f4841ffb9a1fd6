#include "hmd/feature_reports.h"

#include <algorithm>
#include <cmath>

#include "hmd/bytes.h"

namespace photovr::hmd {
namespace {

template <class R>
std::vector<uint8_t> header(const R& r) {
  std::vector<uint8_t> b(R::kSize, 0);
  b[0] = R::kId;
  putLe16(&b[1], r.commandId);
  return b;
}

// ID and length checks shared by every feature report.
template <class R>
Reject checkFrame(std::span<const uint8_t> b) {
  if (b.empty()) return Reject::Empty;
  if (b[0] != R::kId) return Reject::WrongId;
  if (b.size() < R::kSize) return Reject::Short;
  return Reject::None;
}

template <class R>
Decoded<R> finish(const R& r, bool plausible, DecodeStats* stats) {
  return plausible ? accepted(r, stats) : rejected<R>(Reject::OutOfRange, stats);
}

uint16_t fixed(double v, int bits) {
  return uint16_t(std::lround(v * double(1 << bits)));
}

}  // namespace

std::vector<uint8_t> encode(const ConfigReport& r) {
  auto b = header(r);
  b[3] = r.flags;
  b[4] = r.packetInterval;
  putLe16(&b[5], r.sampleRate);
  return b;
}

Decoded<ConfigReport> decodeConfig(std::span<const uint8_t> b, DecodeStats* stats) {
  if (Reject e = checkFrame<ConfigReport>(b); e != Reject::None)
    return rejected<ConfigReport>(e, stats);
  const ConfigReport r{le16(&b[1]), b[3], b[4], le16(&b[5])};
  return finish(r, r.sampleRate > 0, stats);
}

std::vector<uint8_t> encode(const RangeReport& r) {
  auto b = header(r);
  b[3] = r.accelG;
  putLe16(&b[4], r.gyroDegPerS);
  putLe16(&b[6], r.magMilliGauss);
  return b;
}

Decoded<RangeReport> decodeRange(std::span<const uint8_t> b, DecodeStats* stats) {
  if (Reject e = checkFrame<RangeReport>(b); e != Reject::None)
    return rejected<RangeReport>(e, stats);
  const RangeReport r{le16(&b[1]), b[3], le16(&b[4]), le16(&b[6])};
  // dk2.md §2: accel 2/4/8/16 g, gyro 250-2000 deg/s, mag 4000-16000 mGauss.
  const bool accelOk = r.accelG == 2 || r.accelG == 4 || r.accelG == 8 || r.accelG == 16;
  const bool ok = accelOk && r.gyroDegPerS >= 250 && r.gyroDegPerS <= 2000 &&
                  r.magMilliGauss >= 4000 && r.magMilliGauss <= 16000;
  return finish(r, ok, stats);
}

std::vector<uint8_t> encode(const DisplayInfoReport& r) {
  auto b = header(r);
  b[3] = r.distortionType;
  putLe16(&b[4], r.hResolution);
  putLe16(&b[6], r.vResolution);
  const uint32_t lengths[6] = {r.widthUm,          r.heightUm,           r.verticalCentreUm,
                               r.lensSeparationUm, r.lensDistanceLeftUm, r.lensDistanceRightUm};
  for (int i = 0; i < 6; ++i) putLe32(&b[8 + 4 * i], lengths[i]);
  for (int i = 0; i < 6; ++i) putLeFloat(&b[32 + 4 * i], r.distortion[i]);
  return b;
}

Decoded<DisplayInfoReport> decodeDisplayInfo(std::span<const uint8_t> b, DecodeStats* stats) {
  if (Reject e = checkFrame<DisplayInfoReport>(b); e != Reject::None)
    return rejected<DisplayInfoReport>(e, stats);
  DisplayInfoReport r;
  r.commandId = le16(&b[1]);
  r.distortionType = b[3];
  r.hResolution = le16(&b[4]);
  r.vResolution = le16(&b[6]);
  uint32_t* lengths[6] = {&r.widthUm,          &r.heightUm,           &r.verticalCentreUm,
                          &r.lensSeparationUm, &r.lensDistanceLeftUm, &r.lensDistanceRightUm};
  for (int i = 0; i < 6; ++i) *lengths[i] = le32(&b[8 + 4 * i]);
  for (int i = 0; i < 6; ++i) r.distortion[i] = leFloat(&b[32 + 4 * i]);
  // A panel has pixels and a size, the lenses sit on it and the floats are numbers.
  const bool ok = r.hResolution > 0 && r.vResolution > 0 && r.widthUm > 0 && r.heightUm > 0 &&
                  r.lensSeparationUm < r.widthUm && r.verticalCentreUm <= r.heightUm &&
                  std::all_of(r.distortion.begin(), r.distortion.end(),
                              [](float f) { return std::isfinite(f); });
  return finish(r, ok, stats);
}

std::vector<uint8_t> encode(const TrackingLedsReport& r) {
  auto b = header(r);
  b[3] = r.pattern;
  putLe16(&b[4], r.flags);
  putLe16(&b[6], r.exposureUs);
  putLe16(&b[8], r.periodUs);
  putLe16(&b[10], r.vsyncOffset);
  b[12] = r.dutyCycle;
  return b;
}

Decoded<TrackingLedsReport> decodeTrackingLeds(std::span<const uint8_t> b, DecodeStats* stats) {
  if (Reject e = checkFrame<TrackingLedsReport>(b); e != Reject::None)
    return rejected<TrackingLedsReport>(e, stats);
  const TrackingLedsReport r{le16(&b[1]), b[3],         le16(&b[4]), le16(&b[6]),
                             le16(&b[8]), le16(&b[10]), b[12]};
  return finish(r, (r.flags & ~0x3F) == 0, stats);  // only bits 0-5 are defined
}

std::vector<uint8_t> encode(const KeepAliveReport& r) {
  auto b = header(r);
  b[3] = r.reportId;
  putLe16(&b[4], r.intervalMs);
  return b;
}

Decoded<KeepAliveReport> decodeKeepAlive(std::span<const uint8_t> b, DecodeStats* stats) {
  if (Reject e = checkFrame<KeepAliveReport>(b); e != Reject::None)
    return rejected<KeepAliveReport>(e, stats);
  const KeepAliveReport r{le16(&b[1]), b[3], le16(&b[4])};
  return finish(r, r.intervalMs > 0, stats);
}

LensDistortionReport LensDistortionReport::firmwareDefault() {
  LensDistortionReport r;
  r.eyeReliefUm = 17000;
  const double k[11] = {1.003, 1.02, 1.042, 1.066, 1.094, 1.126, 1.162, 1.203, 1.25, 1.31, 1.38};
  for (int i = 0; i < 11; ++i) r.k[i] = fixed(k[i], 14);
  r.maxR = fixed(1.0, 14);
  r.metresPerTanAngle = fixed(0.036, 19);
  const double ca[4] = {-0.015, -0.02, 0.025, 0.02};
  for (int i = 0; i < 4; ++i) r.chroma[i] = uint16_t(0x8000 + std::lround(ca[i] * (1 << 19)));
  return r;
}

std::vector<uint8_t> encode(const LensDistortionReport& r) {
  auto b = header(r);
  b[3] = r.numEntries;
  b[4] = r.index;
  b[5] = r.bitmask;
  putLe16(&b[6], r.lensType);
  putLe16(&b[8], r.version);
  putLe16(&b[10], r.eyeReliefUm);
  for (int i = 0; i < 11; ++i) putLe16(&b[12 + 2 * i], r.k[i]);
  putLe16(&b[34], r.maxR);
  putLe16(&b[36], r.metresPerTanAngle);
  for (int i = 0; i < 4; ++i) putLe16(&b[38 + 2 * i], r.chroma[i]);
  return b;
}

Decoded<LensDistortionReport> decodeLensDistortion(std::span<const uint8_t> b, DecodeStats* stats) {
  if (Reject e = checkFrame<LensDistortionReport>(b); e != Reject::None)
    return rejected<LensDistortionReport>(e, stats);
  LensDistortionReport r;
  r.commandId = le16(&b[1]);
  r.numEntries = b[3];
  r.index = b[4];
  r.bitmask = b[5];
  r.lensType = le16(&b[6]);
  r.version = le16(&b[8]);
  r.eyeReliefUm = le16(&b[10]);
  for (int i = 0; i < 11; ++i) r.k[i] = le16(&b[12 + 2 * i]);
  r.maxR = le16(&b[34]);
  r.metresPerTanAngle = le16(&b[36]);
  for (int i = 0; i < 4; ++i) r.chroma[i] = le16(&b[38 + 2 * i]);
  if (r.version != LensDistortionReport::kCatmullRom10)
    return rejected<LensDistortionReport>(Reject::UnsupportedVersion, stats);
  // The inverse (lens.h) needs a positive, non-decreasing scale curve: K[0] > 0 and K
  // sorted; MaxR and the metres-per-tan-angle scale must be non-zero.
  const bool ok = r.k[0] > 0 && std::is_sorted(r.k.begin(), r.k.end()) && r.maxR > 0 &&
                  r.metresPerTanAngle > 0 && r.index < r.numEntries;
  return finish(r, ok, stats);
}

}  // namespace photovr::hmd
