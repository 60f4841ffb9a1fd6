#include "gl/gbuffer_readback.h"

#include <cstring>

#include "gl/gl_api.h"

namespace photovr::gl {
namespace {

template <typename T>
void copyOut(const uint8_t* src, std::vector<T>& dst, size_t count) {
  dst.resize(count);
  std::memcpy(dst.data(), src, count * sizeof(T));
}

}  // namespace

GBufferReadback::GBufferReadback(const GBufferPass& pass, GBufferRead what) : pass_(pass) {
  using T = GBufferTarget;
  targets_ = {{pass.texture(T::Visibility), GL_RGBA_INTEGER, GL_UNSIGNED_INT, 16}};
  if (what == GBufferRead::All)
    targets_.insert(targets_.end(), {{pass.texture(T::Normal), GL_RGBA, GL_FLOAT, 16},
                                     {pass.texture(T::BaseColor), GL_RGBA, GL_FLOAT, 16},
                                     {pass.texture(T::Material), GL_RGBA, GL_FLOAT, 16},
                                     {pass.texture(T::Emission), GL_RGBA, GL_FLOAT, 16},
                                     {pass.texture(T::Motion), GL_RG, GL_FLOAT, 8},
                                     {pass.depthTexture(), GL_DEPTH_COMPONENT, GL_FLOAT, 4}});
  const size_t pixels = size_t(pass.width()) * pass.height();
  buffers_.resize(targets_.size());
  api::CreateBuffers(GLsizei(buffers_.size()), buffers_.data());
  for (size_t t = 0; t < targets_.size(); ++t)
    api::NamedBufferStorage(buffers_[t], GLsizeiptr(2 * pixels * targets_[t].pixelBytes), nullptr,
                            GL_MAP_READ_BIT | GL_CLIENT_STORAGE_BIT);
}

GBufferReadback::~GBufferReadback() {
  if (fence_) api::DeleteSync(static_cast<GLsync>(fence_));
  api::DeleteBuffers(GLsizei(buffers_.size()), buffers_.data());
}

void GBufferReadback::start(int eyeCount) {
  const int w = pass_.width(), h = pass_.height();
  const size_t layerBytes = size_t(w) * h;
  for (size_t t = 0; t < targets_.size(); ++t) {
    api::BindBuffer(GL_PIXEL_PACK_BUFFER, buffers_[t]);
    // With a pack buffer bound the "pixels" argument is an offset into it.
    api::GetTextureSubImage(targets_[t].texture, 0, 0, 0, 0, w, h, eyeCount, targets_[t].format,
                            targets_[t].type,
                            GLsizei(eyeCount * layerBytes * targets_[t].pixelBytes), nullptr);
  }
  api::BindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  fence_ = api::FenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
  api::Flush();  // start the copies now, do not wait for the next GL call
  eyeCount_ = eyeCount;
}

void GBufferReadback::finish(std::array<GBufferImage, 2>& out) {
  const GLsync sync = static_cast<GLsync>(fence_);
  api::ClientWaitSync(sync, GL_SYNC_FLUSH_COMMANDS_BIT, ~GLuint64(0));
  api::DeleteSync(sync);
  fence_ = nullptr;
  const int w = pass_.width(), h = pass_.height();
  const size_t n = size_t(w) * h;
  std::vector<const uint8_t*> maps(targets_.size());
  for (size_t t = 0; t < targets_.size(); ++t)
    maps[t] = static_cast<const uint8_t*>(api::MapNamedBufferRange(
        buffers_[t], 0, GLsizeiptr(eyeCount_ * n * targets_[t].pixelBytes), GL_MAP_READ_BIT));
  for (int e = 0; e < eyeCount_; ++e) {
    GBufferImage& g = out[e];
    g.width = w;
    g.height = h;
    auto at = [&](size_t t) { return maps[t] + size_t(e) * n * targets_[t].pixelBytes; };
    copyOut(at(0), g.visibility, n);
    if (targets_.size() == 1) {
      g.clearAllButVisibility();
      continue;
    }
    copyOut(at(1), g.normal, n);
    copyOut(at(2), g.baseColor, n);
    copyOut(at(3), g.material, n);
    copyOut(at(4), g.emission, n);
    copyOut(at(5), g.motion, n);
    copyOut(at(6), g.depth, n);
  }
  for (unsigned b : buffers_) api::UnmapNamedBuffer(b);
}

}  // namespace photovr::gl
