// A 64-bit content hash of a scene (geometry, instances, materials, textures, lights,
// environment), for caching results that depend on what is rendered, not on file names.
#pragma once

#include <cstdint>
#include <string>

#include "core/scene.h"

namespace photovr {

class Hasher {
 public:
  Hasher& bytes(const void* data, size_t size);
  template <typename T>
  Hasher& value(const T& v) {
    return bytes(&v, sizeof v);
  }
  template <typename T>
  Hasher& vector(const std::vector<T>& v) {
    return value(v.size()).bytes(v.data(), v.size() * sizeof(T));
  }
  Hasher& text(const std::string& s) { return value(s.size()).bytes(s.data(), s.size()); }
  uint64_t digest() const { return state_; }

 private:
  uint64_t state_ = 0xcbf29ce484222325ull;  // FNV-1a 64 offset basis
};

uint64_t hashScene(const Scene& scene);
std::string hexDigest(uint64_t h);

}  // namespace photovr
