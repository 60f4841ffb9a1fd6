#include "gl/compositor.h"

#include <string>

#include "core/error.h"
#include "gl/context.h"
#include "gl/gl_api.h"
#include "gl/textures.h"
#include "shaders/compositor_shared.h"

namespace photovr::gl {
namespace {

static_assert(sizeof(shared::ReprojectUniforms) == 64 + 4 * 16, "std140 ReprojectUniforms");
static_assert(sizeof(shared::DistortUniforms) == 8 * 16, "std140 DistortUniforms");

void checkEyeCount(const char* what, int eyeCount) {
  if (eyeCount < 1 || eyeCount > 2)
    throw UsageError(std::string(what) + ": eye count must be 1 or 2");
}

}  // namespace

// ---------------------------------------------------------------------------------------
// Re-projection

Reprojector::Reprojector(int w, int h, const ReprojectParams& params)
    : width_(w),
      height_(h),
      params_(params),
      program_(
          {{GL_VERTEX_SHADER, "reproject_vert.glsl"}, {GL_FRAGMENT_SHADER, "reproject_frag.glsl"}},
          {}) {
  if (w < 1 || h < 1) throw UsageError("reprojector: empty image");
  inColor_ = makeArrayTexture(GL_RGBA32F, w, h, 2);
  inDepth_ = makeArrayTexture(GL_R32F, w, h, 2);
  color_ = makeArrayTexture(GL_RGBA16F, w, h, 2);
  depth_ = makeArrayTexture(GL_DEPTH_COMPONENT32F, w, h, 2);
  api::ClearTexImage(inColor_, 0, GL_RGBA, GL_FLOAT, nullptr);
  api::ClearTexImage(inDepth_, 0, GL_RED, GL_FLOAT, nullptr);
  uniforms_ = makeDynamicBuffer(sizeof(shared::ReprojectUniforms));
  api::CreateVertexArrays(1, &vao_);
  api::CreateFramebuffers(1, &fbo_);
}

Reprojector::~Reprojector() {
  const GLuint t[] = {inColor_, inDepth_, color_, depth_};
  api::DeleteTextures(4, t);
  api::DeleteBuffers(1, &uniforms_);
  api::DeleteVertexArrays(1, &vao_);
  api::DeleteFramebuffers(1, &fbo_);
}

void Reprojector::upload(int eye, const glm::vec4* color, const float* depth) {
  if (eye < 0 || eye > 1 || !color || !depth) throw UsageError("reprojector: bad upload");
  api::PixelStorei(GL_UNPACK_ALIGNMENT, 4);
  api::TextureSubImage3D(inColor_, 0, 0, 0, eye, width_, height_, 1, GL_RGBA, GL_FLOAT, color);
  api::TextureSubImage3D(inDepth_, 0, 0, 0, eye, width_, height_, 1, GL_RED, GL_FLOAT, depth);
}

void Reprojector::run(const std::array<EyeCamera, 2>& from, const std::array<EyeCamera, 2>& to,
                      int eyeCount) {
  run(inColor_, inDepth_, from, to, eyeCount);
}

void Reprojector::run(unsigned colorArray, unsigned depthArray,
                      const std::array<EyeCamera, 2>& from, const std::array<EyeCamera, 2>& to,
                      int eyeCount) {
  checkEyeCount("reprojector", eyeCount);
  for (int e = 0; e < eyeCount; ++e) {
    if (from[e].width != width_ || from[e].height != height_ || to[e].width != width_ ||
        to[e].height != height_)
      throw UsageError("reprojector: cameras of eye " + std::to_string(e) + " are not " +
                       std::to_string(width_) + "x" + std::to_string(height_));
    if (from[e].zfar != 0.0f) throw UsageError("reprojector: pose A needs infinite reversed-Z");
  }
  api::ClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
  api::Enable(GL_DEPTH_TEST);
  api::DepthFunc(GL_GEQUAL);  // sky (depth 0) must pass against the cleared 0
  api::DepthMask(GL_TRUE);
  api::Disable(GL_CULL_FACE);
  api::BindFramebuffer(GL_FRAMEBUFFER, fbo_);
  api::Viewport(0, 0, width_, height_);
  api::BindVertexArray(vao_);
  program_.use();
  api::BindTextureUnit(COMP_R_COLOR, colorArray);
  api::BindTextureUnit(COMP_R_DEPTH, depthArray);
  const GLenum drawBuffer = GL_COLOR_ATTACHMENT0;
  api::NamedFramebufferDrawBuffers(fbo_, 1, &drawBuffer);
  if (params_.gridStep < 1 || params_.gridStep > 64)
    throw UsageError("reprojector: grid step must be in [1, 64]");
  const int step = params_.gridStep;
  const GLsizei vertices =
      GLsizei((width_ + step - 1) / step + 1) * GLsizei((height_ + step - 1) / step + 1) * 6;
  for (int e = 0; e < eyeCount; ++e) {
    const EyeCamera& a = from[e];
    const EyeCamera& b = to[e];
    shared::ReprojectUniforms u{};
    u.aEyeToBClip = b.projection() * b.view() * a.pose.toWorld();
    u.aFov = {a.fov.left, a.fov.right, a.fov.up, a.fov.down};
    u.aJitter = {a.jitter.x, a.jitter.y, a.znear, 0.0f};
    u.params = {params_.depthRatio, params_.areaRatio, params_.fillDepthScale, float(step)};
    u.size = {width_, height_, width_, height_};
    api::NamedBufferSubData(uniforms_, 0, sizeof(u), &u);
    api::BindBufferBase(GL_UNIFORM_BUFFER, COMP_REPROJECT_BINDING, uniforms_);
    program_.set("uEye", e);
    api::NamedFramebufferTextureLayer(fbo_, GL_COLOR_ATTACHMENT0, color_, 0, e);
    api::NamedFramebufferTextureLayer(fbo_, GL_DEPTH_ATTACHMENT, depth_, 0, e);
    if (api::CheckNamedFramebufferStatus(fbo_, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw ContextError("reprojector: incomplete framebuffer");
    const GLfloat zero[4] = {0, 0, 0, 0};
    api::ClearNamedFramebufferfv(fbo_, GL_COLOR, 0, zero);
    api::ClearNamedFramebufferfv(fbo_, GL_DEPTH, 0, zero);
    api::DrawArrays(GL_TRIANGLES, 0, vertices);
  }
  api::BindVertexArray(0);
  api::BindFramebuffer(GL_FRAMEBUFFER, 0);
  api::DepthFunc(GL_GREATER);
  api::Disable(GL_DEPTH_TEST);
}

std::vector<glm::vec4> Reprojector::readColor(int eye) const {
  return readTextureLayer<glm::vec4>(color_, GL_RGBA, GL_FLOAT, width_, height_, eye);
}

std::vector<float> Reprojector::readDepth(int eye) const {
  return readTextureLayer<float>(depth_, GL_DEPTH_COMPONENT, GL_FLOAT, width_, height_, eye);
}

ReprojectStats Reprojector::stats(int eye) const {
  ReprojectStats s;
  for (const glm::vec4& c : readColor(eye)) {
    if (c.a > 0.75f)
      ++s.reprojected;
    else if (c.a > 0.25f)
      ++s.filled;
    else
      ++s.uncovered;
  }
  return s;
}

// ---------------------------------------------------------------------------------------
// Distortion

shared::DistortUniforms distortUniforms(const LensParams& lens, int eye, const FovTangents& fov,
                                        int eyeWidth, int eyeHeight, bool footprint) {
  shared::DistortUniforms u{};
  const auto& k = lens.k;
  u.k0 = {k[0], k[1], k[2], k[3]};
  u.k1 = {k[4], k[5], k[6], k[7]};
  u.k2 = {k[8], k[9], k[10], lens.maxR};
  u.chroma = {lens.chroma[0], lens.chroma[1], lens.chroma[2], lens.chroma[3]};
  const glm::vec2 c = lens.lensCentre[size_t(eye)], s = lens.screenToLensScale;
  u.lens = {c.x, c.y, s.x, s.y};
  u.fov = {fov.left, fov.right, fov.up, fov.down};
  const int halfW = lens.hResolution / 2;
  u.panel = {halfW, lens.vResolution, eye * halfW, eye};
  u.eyeSize = {eyeWidth, eyeHeight, footprint ? 1 : 0, 0};
  return u;
}

Distorter::Distorter(const LensParams& lens, int eyeWidth, int eyeHeight,
                     const std::array<FovTangents, 2>& eyeFov)
    : lens_(lens),
      eyeWidth_(eyeWidth),
      eyeHeight_(eyeHeight),
      fov_(eyeFov),
      program_({{GL_COMPUTE_SHADER, "distort.comp"}}, {}) {
  if (lens.hResolution < 2 || lens.hResolution % 2 || lens.vResolution < 1)
    throw UsageError("distorter: the panel needs an even width and a height");
  if (eyeWidth < 1 || eyeHeight < 1) throw UsageError("distorter: empty eye buffer");
  panel_ = makeTexture2D(GL_RGBA16F, lens.hResolution, lens.vResolution);
  tanRG_ = makeTexture2D(GL_RGBA32F, lens.hResolution, lens.vResolution);
  tanB_ = makeTexture2D(GL_RGBA32F, lens.hResolution, lens.vResolution);
  footprint_ = makeArrayTexture(GL_R32UI, eyeWidth, eyeHeight, 2);
  api::ClearTexImage(panel_, 0, GL_RGBA, GL_FLOAT, nullptr);
  api::ClearTexImage(footprint_, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
  uniforms_ = makeDynamicBuffer(sizeof(shared::DistortUniforms));
  // Bilinear with clamp-to-edge, as the debug path's explicit taps (whatever filter the
  // eye array itself carries: the denoiser's and the re-projector's are GL_NEAREST).
  linearSampler_ = makeLinearSampler();
}

Distorter::~Distorter() {
  const GLuint t[] = {panel_, tanRG_, tanB_, footprint_};
  api::DeleteTextures(4, t);
  api::DeleteBuffers(1, &uniforms_);
  api::DeleteSamplers(1, &linearSampler_);
}

void Distorter::run(unsigned eyeArray, int eyeCount, bool footprint) {
  checkEyeCount("distorter", eyeCount);
  const int halfW = lens_.hResolution / 2, h = lens_.vResolution;
  if (footprint) api::ClearTexImage(footprint_, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
  program_.use();
  api::BindTextureUnit(COMP_D_EYE, eyeArray);
  api::BindSampler(COMP_D_EYE, footprint ? 0 : linearSampler_);
  api::BindImageTexture(COMP_I_PANEL, panel_, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
  api::BindImageTexture(COMP_I_TAN_RG, tanRG_, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  api::BindImageTexture(COMP_I_TAN_B, tanB_, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  api::BindImageTexture(COMP_I_FOOTPRINT, footprint_, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R32UI);
  for (int e = 0; e < eyeCount; ++e) {
    const shared::DistortUniforms u =
        distortUniforms(lens_, e, fov_[e], eyeWidth_, eyeHeight_, footprint);
    api::NamedBufferSubData(uniforms_, 0, sizeof(u), &u);
    api::BindBufferBase(GL_UNIFORM_BUFFER, COMP_DISTORT_BINDING, uniforms_);
    api::DispatchCompute(GLuint((halfW + COMP_GROUP - 1) / COMP_GROUP),
                         GLuint((h + COMP_GROUP - 1) / COMP_GROUP), 1);
    api::MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT |
                       GL_UNIFORM_BARRIER_BIT);
  }
  api::BindSampler(COMP_D_EYE, 0);
}

std::vector<glm::vec4> Distorter::readPanel() const {
  return readTextureLayer<glm::vec4>(panel_, GL_RGBA, GL_FLOAT, lens_.hResolution,
                                     lens_.vResolution, 0);
}

std::vector<DistortSample> Distorter::readSamples() const {
  const auto rg = readTextureLayer<glm::vec4>(tanRG_, GL_RGBA, GL_FLOAT, lens_.hResolution,
                                              lens_.vResolution, 0);
  const auto b = readTextureLayer<glm::vec4>(tanB_, GL_RGBA, GL_FLOAT, lens_.hResolution,
                                             lens_.vResolution, 0);
  std::vector<DistortSample> out(rg.size());
  for (size_t i = 0; i < rg.size(); ++i)
    out[i] = {{glm::vec2(rg[i].x, rg[i].y), glm::vec2(rg[i].z, rg[i].w), glm::vec2(b[i].x, b[i].y)},
              b[i].z > 0.5f};
  return out;
}

std::vector<uint8_t> Distorter::readFootprint(int eye) const {
  const auto v = readTextureLayer<uint32_t>(footprint_, GL_RED_INTEGER, GL_UNSIGNED_INT, eyeWidth_,
                                            eyeHeight_, eye);
  std::vector<uint8_t> out(v.size());
  for (size_t i = 0; i < v.size(); ++i) out[i] = v[i] ? 1 : 0;
  return out;
}

}  // namespace photovr::gl
