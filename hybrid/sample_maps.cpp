#include "hybrid/sample_maps.h"

#include <cstdio>

#include "core/error.h"
#include "hmd/lens_maps.h"

namespace photovr {
namespace {

constexpr const char* kNames[] = {"uniform", "hidden-area", "lens-matched", "thesis-zones"};

}  // namespace

SampleMapKind parseSampleMapKind(const std::string& name) {
  for (int k = 0; k < 4; ++k)
    if (name == kNames[k]) return SampleMapKind(k);
  throw UsageError("--sampling: '" + name +
                   "' is not one of uniform, hidden-area, lens-matched, thesis-zones");
}

const char* sampleMapKindName(SampleMapKind kind) {
  return kNames[int(kind)];
}

StereoSampleMaps lensSampleMaps(SampleMapKind kind, const StereoLayout& layout, int spp,
                                const hmd::LensModel& lens) {
  StereoSampleMaps maps;
  if (kind == SampleMapKind::Uniform) return maps;
  for (int e = 0; e < 2; ++e) {
    const hmd::EyeBufferSpec spec = hmd::EyeBufferSpec::of(layout, Eye(e));
    if (kind == SampleMapKind::LensMatched) {
      maps[e] = SampleMap(hmd::lensMatchedSpp(lens, spec, spp));
    } else if (kind == SampleMapKind::ThesisZones) {
      maps[e] = SampleMap(hmd::thesisZoneSpp(spec.width, spec.height, spp));
    } else {
      const std::vector<uint8_t> hidden = hmd::hiddenAreaMask(lens, spec);
      std::vector<uint16_t> counts(hidden.size());
      for (size_t i = 0; i < hidden.size(); ++i) counts[i] = hidden[i] ? 0 : uint16_t(spp);
      maps[e] = SampleMap(std::move(counts));
    }
  }
  return maps;
}

std::string describeSampleMaps(const StereoSampleMaps& maps) {
  if (maps[0].isUniform()) return "uniform";
  size_t zero = 0, total = 0, n = 0;
  for (const SampleMap& m : maps)
    for (uint16_t s : m.perPixel()) zero += s == 0, total += s, ++n;
  char buf[128];
  std::snprintf(buf, sizeof buf, "%.1f %% of pixels not traced, %.2f samples per pixel on average",
                100.0 * double(zero) / double(n), double(total) / double(n));
  return buf;
}

}  // namespace photovr
