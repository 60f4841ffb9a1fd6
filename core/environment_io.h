// Environment maps: equirectangular radiance images.
#pragma once

#include <string>

#include "core/scene.h"

namespace photovr {

// Loads an equirectangular .hdr or .exr (anything OpenImageIO reads as float) as an
// Environment of type Map: RGB, gray replicated, alpha dropped, row 0 at the top.
// Throws InputError("<path>: <problem>") for a missing, unreadable or corrupt file and for
// a non-finite or negative pixel, naming the first one: radiance cannot be negative, and
// silently clamping would hide a broken export. An image that is not 2:1 still loads; the
// returned warning says so (empty when there is nothing to report).
Environment loadEnvironment(const std::string& path, std::string* warning = nullptr);

}  // namespace photovr
