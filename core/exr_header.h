// A walk over an OpenEXR file's header attributes before OpenImageIO opens it. OpenEXR
// allocates and reads whatever size an attribute claims: one flipped byte in a 480-byte
// file's string length made it allocate 956 MB and take 4 s to fail (found by fuzzing
// environment maps). Each attribute's size must fit in what is left of the file.
#pragma once

#include <string>

namespace photovr {

// Throws InputError(path, ...) naming the first attribute whose claimed size exceeds the
// bytes left after it, or a header that ends before its terminator. Returns quietly for a
// file that is not OpenEXR (no magic number), leaving it to its own reader.
void checkExrHeader(const std::string& path);

}  // namespace photovr
