// Environment maps: equirectangular radiance images.
#pragma once

#include <string>

#include "core/scene.h"

namespace photovr {

// Loads an equirectangular .hdr or .exr (anything OpenImageIO reads as float) as an
// Environment of type Map: RGB, gray replicated, alpha dropped, row 0 at the top.
// Throws InputError("<path>: <problem>") for a missing, unreadable or corrupt file and for
// a non-finite or negative pixel, naming the first one: radiance cannot be negative, and
// silently clamping would hide a broken export. Negatives small enough to be a lossy
// codec's error (DWAA/DWAB, B44: up to 1/16 of the largest value of their channel in the
// pixel's 8x8 block, environment_io.cpp derives it) are clamped to 0, and the warning gives
// their count and the most negative. An image that is not 2:1 still loads, with a warning.
// The warning is one line, empty when there is nothing to report.
Environment loadEnvironment(const std::string& path, std::string* warning = nullptr);

}  // namespace photovr
