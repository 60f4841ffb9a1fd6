// Per-pixel sample counts for the hybrid from the DK2's lens (hmd/lens_maps.h).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "core/camera.h"

namespace photovr::app {

// 'kind': hidden-area (spp where the lens shows the pixel, 0 elsewhere), lens-matched
// (up to 'spp', proportional to the lens's magnification), thesis-zones (Algorithm 6).
// Empty maps for "uniform". Row 0 is the lowest, as the G-buffer. Overscan pixels a head
// turn within the layout's margin can bring into the lens count as seen.
std::array<std::vector<uint16_t>, 2> lensSampleMaps(const std::string& kind,
                                                    const StereoLayout& layout, int spp);

// Pixels with zero samples and the mean samples per pixel, for the report.
std::string describeSampleMaps(const std::array<std::vector<uint16_t>, 2>& maps);

}  // namespace photovr::app
