#include "app/sample_maps.h"

#include <cstdio>

#include "hmd/lens.h"
#include "hmd/lens_maps.h"

namespace photovr::app {

std::array<std::vector<uint16_t>, 2> lensSampleMaps(const std::string& kind,
                                                    const StereoLayout& layout, int spp) {
  std::array<std::vector<uint16_t>, 2> maps;
  if (kind == "uniform") return maps;
  const hmd::LensModel lens;  // the documented DK2 defaults (dk2.md §6)
  for (int e = 0; e < 2; ++e) {
    const hmd::EyeBufferSpec spec = hmd::EyeBufferSpec::of(layout, Eye(e));
    if (kind == "lens-matched") {
      maps[e] = hmd::lensMatchedSpp(lens, spec, spp);
    } else if (kind == "thesis-zones") {
      maps[e] = hmd::thesisZoneSpp(spec.width, spec.height, spp);
    } else {
      const std::vector<uint8_t> hidden = hmd::hiddenAreaMask(lens, spec);
      maps[e].resize(hidden.size());
      for (size_t i = 0; i < hidden.size(); ++i) maps[e][i] = hidden[i] ? 0 : uint16_t(spp);
    }
  }
  return maps;
}

std::string describeSampleMaps(const std::array<std::vector<uint16_t>, 2>& maps) {
  if (maps[0].empty()) return "uniform";
  size_t zero = 0, total = 0, n = 0;
  for (const auto& m : maps)
    for (uint16_t s : m) zero += s == 0, total += s, ++n;
  char buf[128];
  std::snprintf(buf, sizeof buf, "%.1f %% of pixels not traced, %.2f samples per pixel on average",
                100.0 * double(zero) / double(n), double(total) / double(n));
  return buf;
}

}  // namespace photovr::app
