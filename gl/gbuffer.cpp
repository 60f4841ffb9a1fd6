#include "gl/gbuffer.h"

#include "gl/context.h"
#include "gl/draw_stats.h"
#include "gl/gl_api.h"
#include "shaders/gbuffer_shared.h"

namespace photovr::gl {
namespace {

static_assert(sizeof(shared::FrameUniforms) == 6 * 64 + 10 * 16 + 16, "std140 FrameUniforms");

struct TargetFormat {
  GLenum internal, format, type;
};

// Half floats suffice for unit normals, albedo and emission (11-bit mantissa, ~5e-4
// relative); they cost ~8 % less than 32-bit on llvmpipe (platform.md). The visibility
// record is exact (32-bit integers holding float bits).
constexpr TargetFormat kFormats[] = {
    {GL_RGBA32UI, GL_RGBA_INTEGER, GL_UNSIGNED_INT},  // visibility
    {GL_RGBA16F, GL_RGBA, GL_FLOAT},                  // normal
    {GL_RGBA16F, GL_RGBA, GL_FLOAT},                  // base colour
    {GL_RGBA16F, GL_RGBA, GL_FLOAT},                  // material
    {GL_RGBA16F, GL_RGBA, GL_FLOAT},                  // emission
    {GL_RG16F, GL_RG, GL_FLOAT},                      // motion
};
constexpr int kTargets = int(GBufferTarget::Count);

GLuint makeTexture(GLenum target, GLenum internal, int w, int h, int layers) {
  GLuint t = 0;
  api::CreateTextures(target, 1, &t);
  if (target == GL_TEXTURE_2D_ARRAY)
    api::TextureStorage3D(t, 1, internal, w, h, layers);
  else
    api::TextureStorage2D(t, 1, internal, w, h);
  api::TextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  api::TextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  return t;
}

template <typename T>
void readLayer(GLuint tex, const TargetFormat& f, int w, int h, int layer, std::vector<T>& out) {
  out.resize(size_t(w) * h);
  api::GetTextureSubImage(tex, 0, 0, 0, layer, w, h, 1, f.format, f.type,
                          GLsizei(out.size() * sizeof(T)), out.data());
}

}  // namespace

GBufferPass::GBufferPass(int w, int h, EyeRouting routing)
    : width_(w),
      height_(h),
      routing_(Context::currentContextHasExtension("GL_ARB_shader_viewport_layer_array")
                   ? routing
                   : EyeRouting::SideBySide),
      program_({{GL_VERTEX_SHADER, "gbuffer.vert"}, {GL_FRAGMENT_SHADER, "gbuffer.frag"}},
               routing_ == EyeRouting::Layered
                   ? std::vector<std::string>{"PHOTOVR_LAYERED 1\n#extension "
                                              "GL_ARB_shader_viewport_layer_array : require"}
                   : std::vector<std::string>{}) {
  GLint alignment = 0;
  api::GetIntegerv(GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT, &alignment);
  if (alignment <= 0 || sizeof(shared::GpuMaterial) % size_t(alignment) != 0)
    throw ContextError("uniform buffer offset alignment " + std::to_string(alignment) +
                       " does not divide the 256-byte material stride");
  createTargets();
  api::CreateBuffers(1, &frameBuffer_);
  api::NamedBufferStorage(frameBuffer_, sizeof(shared::FrameUniforms), nullptr,
                          GL_DYNAMIC_STORAGE_BIT);
}

GBufferPass::~GBufferPass() {
  api::DeleteFramebuffers(1, &fbo_);
  api::DeleteTextures(kTargets, layers_);
  api::DeleteTextures(1, &depthLayers_);
  api::DeleteTextures(kTargets, wide_);
  api::DeleteTextures(1, &wideDepth_);
  api::DeleteBuffers(1, &frameBuffer_);
}

void GBufferPass::createTargets() {
  const bool layered = routing_ == EyeRouting::Layered;
  for (int t = 0; t < kTargets; ++t) {
    layers_[t] = makeTexture(GL_TEXTURE_2D_ARRAY, kFormats[t].internal, width_, height_, 2);
    if (!layered)
      wide_[t] = makeTexture(GL_TEXTURE_2D, kFormats[t].internal, 2 * width_, height_, 1);
  }
  depthLayers_ = makeTexture(GL_TEXTURE_2D_ARRAY, GL_DEPTH_COMPONENT32F, width_, height_, 2);
  if (!layered)
    wideDepth_ = makeTexture(GL_TEXTURE_2D, GL_DEPTH_COMPONENT32F, 2 * width_, height_, 1);
  api::CreateFramebuffers(1, &fbo_);
  GLenum buffers[kTargets];
  for (int t = 0; t < kTargets; ++t) {
    api::NamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT0 + t, layered ? layers_[t] : wide_[t],
                                 0);
    buffers[t] = GL_COLOR_ATTACHMENT0 + t;
  }
  api::NamedFramebufferTexture(fbo_, GL_DEPTH_ATTACHMENT, layered ? depthLayers_ : wideDepth_, 0);
  api::NamedFramebufferDrawBuffers(fbo_, kTargets, buffers);
  if (api::CheckNamedFramebufferStatus(fbo_, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw ContextError("G-buffer framebuffer is incomplete on this OpenGL implementation");
}

void GBufferPass::uploadFrame(const std::array<EyeCamera, 2>& eyes,
                              const std::array<glm::mat4, 2>& previous) {
  shared::FrameUniforms f{};
  for (int e = 0; e < 2; ++e) {
    const EyeCamera& c = eyes[e];
    f.viewProjection[e] = c.projection() * c.view();
    f.viewProjectionUnjittered[e] = c.unjitteredProjection() * c.view();
    f.previousViewProjection[e] = previous[e];
    f.eyePosition[e] = glm::vec4(c.pose.position, 1.0f);
    f.rayBase[e] = glm::vec4(c.rayBase(), 0.0f);
    f.rayDx[e] = glm::vec4(c.rayDx(), 0.0f);
    f.rayDy[e] = glm::vec4(c.rayDy(), 0.0f);
    f.jitter[e] = glm::vec4(c.jitter, 0.0f, 0.0f);
  }
  f.viewport = glm::vec4(width_, height_, 1.0f / width_, 1.0f / height_);
  api::NamedBufferSubData(frameBuffer_, 0, sizeof(f), &f);
}

void GBufferPass::render(const SceneGpu& scene, const std::array<EyeCamera, 2>& eyes,
                         const std::array<glm::mat4, 2>& previousViewProjection) {
  uploadFrame(eyes, previousViewProjection);
  const bool layered = routing_ == EyeRouting::Layered;
  api::BindFramebuffer(GL_FRAMEBUFFER, fbo_);
  api::Viewport(0, 0, layered ? width_ : 2 * width_, height_);
  const GLuint noHit[4] = {VISIBILITY_NONE, VISIBILITY_NONE, 0, 0};
  api::ClearNamedFramebufferuiv(fbo_, GL_COLOR, 0, noHit);
  const GLfloat zero[4] = {0, 0, 0, 0};
  for (int t = 1; t < kTargets; ++t) api::ClearNamedFramebufferfv(fbo_, GL_COLOR, t, zero);
  const GLfloat farDepth = 0.0f;  // reversed-Z
  api::ClearNamedFramebufferfv(fbo_, GL_DEPTH, 0, &farDepth);
  api::ClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
  api::Enable(GL_DEPTH_TEST);
  api::DepthFunc(GL_GREATER);
  api::DepthMask(GL_TRUE);
  if (!layered) {
    api::Enable(GL_CLIP_DISTANCE0);
    api::Enable(GL_CLIP_DISTANCE1);
  }
  drawMeshes(scene);
  if (!layered) {
    api::Disable(GL_CLIP_DISTANCE0);
    api::Disable(GL_CLIP_DISTANCE1);
    copySideBySideToLayers();
  }
  api::BindFramebuffer(GL_FRAMEBUFFER, 0);
}

void GBufferPass::drawMeshes(const SceneGpu& scene) {
  program_.use();
  api::BindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, scene.instanceBuffer());
  api::BindBufferBase(GL_UNIFORM_BUFFER, 4, frameBuffer_);
  api::FrontFace(GL_CCW);
  api::CullFace(GL_BACK);
  for (const GpuMesh& m : scene.meshes()) {
    if (m.instanceCount == 0) continue;
    // Hardware culling where every instance keeps its winding; the fragment shader culls
    // single-sided back faces of mirrored instances itself.
    const bool cull = !m.anyMirrored && scene.cullBackFaces(m.material);
    cull ? api::Enable(GL_CULL_FACE) : api::Disable(GL_CULL_FACE);
    program_.set("uFirstInstance", m.firstInstance);
    api::BindBufferRange(GL_UNIFORM_BUFFER, 5, scene.materialBuffer(),
                         GLintptr(m.material) * GLintptr(sizeof(shared::GpuMaterial)),
                         sizeof(shared::GpuMaterial));
    for (int s = 0; s < SLOT_COUNT; ++s) api::BindTextureUnit(s, scene.texture(m.material, s));
    api::BindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, m.buffers[0]);
    api::BindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, m.buffers[5]);
    api::BindVertexArray(m.vao);
    drawIndexedTrianglesInstanced(m.indexCount, 2 * m.instanceCount);
  }
  api::BindVertexArray(0);
  api::Disable(GL_CULL_FACE);
}

void GBufferPass::copySideBySideToLayers() {
  for (int e = 0; e < 2; ++e) {
    for (int t = 0; t < kTargets; ++t)
      api::CopyImageSubData(wide_[t], GL_TEXTURE_2D, 0, e * width_, 0, 0, layers_[t],
                            GL_TEXTURE_2D_ARRAY, 0, 0, 0, e, width_, height_, 1);
    api::CopyImageSubData(wideDepth_, GL_TEXTURE_2D, 0, e * width_, 0, 0, depthLayers_,
                          GL_TEXTURE_2D_ARRAY, 0, 0, 0, e, width_, height_, 1);
  }
}

void GBufferPass::finish() const {
  api::Finish();
}

GBufferImage GBufferPass::read(int eye) const {
  GBufferImage img;
  read(eye, img);
  return img;
}

void GBufferPass::read(int eye, GBufferImage& img, GBufferRead what) const {
  img.width = width_;
  img.height = height_;
  const int w = width_, h = height_;
  readLayer(layers_[0], kFormats[0], w, h, eye, img.visibility);
  if (what == GBufferRead::Visibility) return img.clearAllButVisibility();
  readLayer(layers_[1], kFormats[1], w, h, eye, img.normal);
  readLayer(layers_[2], kFormats[2], w, h, eye, img.baseColor);
  readLayer(layers_[3], kFormats[3], w, h, eye, img.material);
  readLayer(layers_[4], kFormats[4], w, h, eye, img.emission);
  readLayer(layers_[5], kFormats[5], w, h, eye, img.motion);
  readLayer(depthLayers_, {GL_DEPTH_COMPONENT32F, GL_DEPTH_COMPONENT, GL_FLOAT}, w, h, eye,
            img.depth);
}

}  // namespace photovr::gl
