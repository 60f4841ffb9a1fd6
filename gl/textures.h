// Small texture and buffer helpers the compositor passes share (GL 4.5 DSA): immutable
// storage with nearest filtering, a layer read back to the CPU, a uniform buffer.
#pragma once

#include <cstddef>
#include <vector>

#include "gl/gl_api.h"

namespace photovr::gl {

// A 'layers'-layer 2D array texture, one level, nearest filtering.
inline GLuint makeArrayTexture(GLenum internal, int w, int h, int layers) {
  GLuint t = 0;
  api::CreateTextures(GL_TEXTURE_2D_ARRAY, 1, &t);
  api::TextureStorage3D(t, 1, internal, w, h, layers);
  api::TextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  api::TextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  return t;
}

// A 2D texture, one level, nearest filtering.
inline GLuint makeTexture2D(GLenum internal, int w, int h) {
  GLuint t = 0;
  api::CreateTextures(GL_TEXTURE_2D, 1, &t);
  api::TextureStorage2D(t, 1, internal, w, h);
  api::TextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  api::TextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  return t;
}

// Layer 'layer' of a w x h texture (a 2D texture's only layer is 0), rows bottom-up,
// after the shader writes before it are made visible.
template <typename T>
std::vector<T> readTextureLayer(GLuint tex, GLenum format, GLenum type, int w, int h, int layer) {
  api::MemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
  api::PixelStorei(GL_PACK_ALIGNMENT, 1);
  std::vector<T> out(size_t(w) * h);
  api::GetTextureSubImage(tex, 0, 0, 0, layer, w, h, 1, format, type,
                          GLsizei(out.size() * sizeof(T)), out.data());
  return out;
}

// A buffer of 'size' bytes updated with NamedBufferSubData.
inline GLuint makeDynamicBuffer(size_t size) {
  GLuint b = 0;
  api::CreateBuffers(1, &b);
  api::NamedBufferStorage(b, GLsizeiptr(size), nullptr, GL_DYNAMIC_STORAGE_BIT);
  return b;
}

// A bilinear, clamp-to-edge sampler object (for arrays created with nearest filtering).
inline GLuint makeLinearSampler() {
  GLuint s = 0;
  api::CreateSamplers(1, &s);
  api::SamplerParameteri(s, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  api::SamplerParameteri(s, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  api::SamplerParameteri(s, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  api::SamplerParameteri(s, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  return s;
}

}  // namespace photovr::gl
