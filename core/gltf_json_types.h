// The types of the glTF 2.0 members photovr reads, checked on the JSON itself before
// tinygltf parses it. tinygltf silently drops an optional member of the wrong type
// (`"translation": "abc"` loads as no translation), so a malformed file would render as a
// different scene instead of failing; this check turns it into one error naming the member,
// e.g. `nodes[3].translation: expected an array of 3 numbers, got a string`.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace photovr {

// Throws InputError(path, ...) for the first member of the wrong type or array length
// among those the loader uses (glTF 2.0 §5, KHR_lights_punctual,
// KHR_materials_emissive_strength, _ior, _specular, _transmission, _volume,
// KHR_texture_transform). Members photovr does not read
// are not checked; JSON that does not parse is left to tinygltf's own message.
void checkGltfJsonTypes(const uint8_t* json, size_t size, const std::string& path);

// The names listed in the root's "extensionsRequired" (glTF 2.0 §3.12), read before
// anything else so that a file needing an extension photovr lacks fails with that, not
// with what tinygltf makes of data the extension encodes. Non-strings, a member of another
// type, and JSON that does not parse give nothing here (left to the checks above).
std::vector<std::string> requiredExtensions(const uint8_t* json, size_t size);

}  // namespace photovr
