// Per-pixel sample counts of both eyes from the headset's lens (hmd/lens_maps.h), as the
// frame pipeline traces them (trace/sample_map.h).
#pragma once

#include <string>

#include "core/camera.h"
#include "hmd/lens.h"
#include "trace/sample_map.h"

namespace photovr {

enum class SampleMapKind {
  Uniform,      // every pixel the frame's spp
  HiddenArea,   // spp where the lens shows the pixel, 0 (not traced) elsewhere
  LensMatched,  // up to spp, proportional to the lens's magnification
  ThesisZones,  // the thesis's Algorithm 6, for comparison
};

// "uniform", "hidden-area", "lens-matched", "thesis-zones"; parse: UsageError otherwise.
SampleMapKind parseSampleMapKind(const std::string& name);
const char* sampleMapKindName(SampleMapKind kind);

// Row 0 is the lowest, as the G-buffer. Overscan pixels a head turn within the layout's
// margin can bring into the lens count as seen.
StereoSampleMaps lensSampleMaps(SampleMapKind kind, const StereoLayout& layout, int spp,
                                const hmd::LensModel& lens = {});

// Pixels with zero samples and the mean samples per pixel, for the report.
std::string describeSampleMaps(const StereoSampleMaps& maps);

}  // namespace photovr
