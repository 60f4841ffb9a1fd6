#include "gl/denoiser.h"

#include <algorithm>
#include <cassert>
#include <utility>

#include "core/error.h"
#include "gl/gbuffer.h"
#include "gl/gl_api.h"
#include "shaders/denoise_shared.h"

namespace photovr::gl {
namespace {

static_assert(sizeof(shared::DenoiseUniforms) == 6 * 16, "std140 DenoiseUniforms");
constexpr int kMaxIterations = 5;

GLuint makeArray(GLenum internal, int w, int h) {
  GLuint t = 0;
  api::CreateTextures(GL_TEXTURE_2D_ARRAY, 1, &t);
  api::TextureStorage3D(t, 1, internal, w, h, 2);
  api::TextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  api::TextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  return t;
}

// Zeroed at creation so that nothing read before its first write is NaN garbage.
GLuint makeCleared(GLenum internal, GLenum format, GLenum type, int w, int h) {
  const GLuint t = makeArray(internal, w, h);
  api::ClearTexImage(t, 0, format, type, nullptr);
  return t;
}

template <typename T>
std::vector<T> readLayer(GLuint tex, GLenum format, GLenum type, int w, int h, int layer) {
  api::MemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
  std::vector<T> out(size_t(w) * h);
  api::GetTextureSubImage(tex, 0, 0, 0, layer, w, h, 1, format, type,
                          GLsizei(out.size() * sizeof(T)), out.data());
  return out;
}

void bindImage(int unit, GLuint tex, GLenum format) {
  api::BindImageTexture(GLuint(unit), tex, 0, GL_TRUE, 0, GL_WRITE_ONLY, format);
}

// Image stores of one pass become visible to the next pass's texel fetches and stores.
void passBarrier() {
  api::MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

}  // namespace

DenoiseMode parseDenoiseMode(const std::string& name) {
  if (name == "off") return DenoiseMode::Off;
  if (name == "temporal") return DenoiseMode::Temporal;
  if (name == "full") return DenoiseMode::Full;
  throw UsageError("--denoise: unknown mode '" + name + "' (expected off, temporal or full)");
}

std::string denoiseModeName(DenoiseMode mode) {
  switch (mode) {
    case DenoiseMode::Off:
      return "off";
    case DenoiseMode::Temporal:
      return "temporal";
    case DenoiseMode::Full:
      return "full";
  }
  return "?";
}

DenoiseGeometry denoiseGeometry(const GBufferPass& g) {
  return {g.texture(GBufferTarget::Visibility), g.texture(GBufferTarget::Normal),
          g.texture(GBufferTarget::Material), g.texture(GBufferTarget::Motion), g.depthTexture()};
}

Denoiser::Denoiser(int w, int h, const DenoiseParams& params)
    : width_(w),
      height_(h),
      params_(params),
      temporal_({{GL_COMPUTE_SHADER, "svgf_temporal.comp"}}, {}),
      firefly_({{GL_COMPUTE_SHADER, "svgf_firefly.comp"}}, {}),
      atrous_({{GL_COMPUTE_SHADER, "svgf_atrous.comp"}}, {}),
      atrousComposite_({{GL_COMPUTE_SHADER, "svgf_atrous.comp"}},
                       {"SVGF_COMPOSITE 1", "SVGF_RESOLVE_FOLLOWS 1"}),
      atrousDiffuse_({{GL_COMPUTE_SHADER, "svgf_atrous.comp"}}, {"SVGF_SPECULAR_DONE 1"}),
      atrousDiffuseComposite_(
          {{GL_COMPUTE_SHADER, "svgf_atrous.comp"}},
          {"SVGF_SPECULAR_DONE 1", "SVGF_COMPOSITE 1", "SVGF_RESOLVE_FOLLOWS 1"}),
      composite_({{GL_COMPUTE_SHADER, "svgf_composite.comp"}}, {}),
      resolve_({{GL_COMPUTE_SHADER, "svgf_resolve.comp"}}, {}) {
  for (GLuint& t : inputs_) t = makeCleared(GL_RGB32F, GL_RGB, GL_FLOAT, w, h);
  for (int i = 0; i < 2; ++i) {
    geometry_[i] = makeCleared(GL_RGBA32UI, GL_RGBA_INTEGER, GL_UNSIGNED_INT, w, h);
    aux_[i] = makeCleared(GL_RGBA16F, GL_RGBA, GL_FLOAT, w, h);
    moments_[i] = makeCleared(GL_RGBA32F, GL_RGBA, GL_FLOAT, w, h);
    for (GLuint* t :
         {&history_[i][0], &history_[i][1], &filterA_[i], &filterB_[i], &resolveHistory_[i]})
      *t = makeCleared(GL_RGBA16F, GL_RGBA, GL_FLOAT, w, h);
  }
  linear_ = makeCleared(GL_RGBA16F, GL_RGBA, GL_FLOAT, w, h);
  composited_ = makeCleared(GL_RGBA16F, GL_RGBA, GL_FLOAT, w, h);
  display_ = makeCleared(GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE, w, h);
  depth_ = makeCleared(GL_R32F, GL_RED, GL_FLOAT, w, h);
  api::CreateBuffers(1, &uniforms_);
  api::NamedBufferStorage(uniforms_, sizeof(shared::DenoiseUniforms), nullptr,
                          GL_DYNAMIC_STORAGE_BIT);
  buildPasses();
}

Denoiser::~Denoiser() {
  api::DeleteTextures(InCount, inputs_);
  for (int i = 0; i < 2; ++i) {
    const GLuint t[] = {geometry_[i],   aux_[i],     moments_[i], history_[i][0],
                        history_[i][1], filterA_[i], filterB_[i], resolveHistory_[i]};
    api::DeleteTextures(GLsizei(std::size(t)), t);
  }
  const GLuint out[] = {linear_, display_, depth_, composited_};
  api::DeleteTextures(GLsizei(std::size(out)), out);
  api::DeleteBuffers(1, &uniforms_);
}

void Denoiser::setParams(const DenoiseParams& params) {
  params_ = params;
  buildPasses();
}

void Denoiser::run(const GBufferPass& gbuffer, const std::array<NoisyEye, 2>& eyes, int eyeCount,
                   DenoiseMode mode, bool resetHistory) {
  run(denoiseGeometry(gbuffer), eyes, eyeCount, mode, resetHistory);
}

void Denoiser::run(const DenoiseGeometry& g, const std::array<NoisyEye, 2>& eyes, int eyeCount,
                   DenoiseMode mode, bool resetHistory) {
  if (eyeCount < 1 || eyeCount > 2) throw UsageError("denoiser: eye count must be 1 or 2");
  if (params_.iterations < 0 || params_.iterations > kMaxIterations)
    throw UsageError("denoiser: iterations must be in [0, 5]");
  eyeCount_ = eyeCount;
  timings_.clear();
  frameIn_ = {g, &eyes, resetHistory};
  passes_[size_t(mode)].run(timing_ ? &timings_ : nullptr);
  frameIn_.eyes = nullptr;
  if (mode == DenoiseMode::Off) {
    historyValid_ = false;  // 'off' does not maintain the history
    return;
  }
  ++frame_;
  historyValid_ = true;
}

// ---------------------------------------------------------------------------------------
// The pass lists. Resources are named by content; "prev.*" is what this frame's namesake
// was last frame (the ping-pong by parity), "history" whichever lobe pair is next frame's
// colour history. Where a pair lives (Lobes) is chosen here, once per list.

namespace {

std::vector<std::string> listInputs() {
  return {"gbuffer.visibility", "gbuffer.normal",     "gbuffer.material", "gbuffer.motion",
          "gbuffer.depth",      "prev.geometry",      "prev.aux",         "prev.moments",
          "prev.history",       "prev.resolveHistory"};
}

}  // namespace

void Denoiser::buildPasses() {
  for (DenoiseMode m : {DenoiseMode::Off, DenoiseMode::Temporal, DenoiseMode::Full})
    passes_[size_t(m)] = buildPasses(m);
}

PassList Denoiser::buildPasses(DenoiseMode mode) {
  // run() refuses other counts before it runs a list.
  const int iterations = std::clamp(params_.iterations, 0, kMaxIterations);
  const bool filter = mode == DenoiseMode::Full && iterations > 0;
  const bool clamp = filter && params_.suppressFireflies;
  const bool historyFiltered = filter && params_.historyFromFirstIteration;
  std::vector<PassDecl> passes = {uploadPass()};
  std::vector<std::string> outputs = {"linear", "display", "depth"};
  if (mode == DenoiseMode::Off) {
    passes.push_back(compositePass({"noisy", Lobes::Noisy}));
    return PassList(listInputs(), outputs, std::move(passes));
  }
  outputs.insert(outputs.end(), {"history", "geometry", "aux", "moments"});
  // The colour history is the temporal output, after the firefly clamp where it runs
  // (DenoiseParams::historyFromFirstIteration says why not the first iteration's output).
  const Colour temporalOut{"temporal", clamp || historyFiltered ? Lobes::FilterA : Lobes::History};
  passes.push_back(temporalPass(temporalOut));
  if (!filter) {
    passes.push_back(compositePass(temporalOut));
  } else {
    addFilterPasses(passes, temporalOut, iterations, clamp, historyFiltered);
    passes.push_back(resolvePass());
    outputs.push_back("resolveHistory");
  }
  return PassList(listInputs(), outputs, std::move(passes));
}

void Denoiser::addFilterPasses(std::vector<PassDecl>& passes, Colour in, int iterations, bool clamp,
                               bool historyFiltered) {
  // The iterations ping-pong between two buffers holding neither stage 0 nor the history;
  // last frame's history is one of them once the temporal pass has read it.
  const bool inA = in.at == Lobes::FilterA;
  const Lobes scratch[2] = {inA ? Lobes::FilterB : Lobes::FilterA,
                            inA ? Lobes::PrevHistory : Lobes::FilterB};
  if (clamp) {
    const Colour out{"firefly", historyFiltered ? scratch[0] : Lobes::History};
    passes.push_back(fireflyPass(in, out));
    in = out;
  }
  for (int i = 0; i < iterations; ++i) {
    const Lobes at = i == 0 && historyFiltered ? Lobes::History
                     : in.at == scratch[0]     ? scratch[1]
                                               : scratch[0];
    const Colour out{"atrous" + std::to_string(i), at};
    passes.push_back(atrousPass(i, i + 1 == iterations, in, out));
    in = out;
  }
}

namespace {

// A pass writing a lobe pair also writes "history" when the pair is next frame's.
std::vector<std::string> colourWrites(const std::string& name, bool isHistory,
                                      std::vector<std::string> more = {}) {
  more.insert(more.begin(), name);
  if (isHistory) more.push_back("history");
  return more;
}

}  // namespace

PassDecl Denoiser::uploadPass() {
  return {"upload", {}, {"noisy", "albedo", "unfiltered", "guide"}, [this] {
            uploadUniforms(frameIn_.reset || !historyValid_);
            upload(*frameIn_.eyes, eyeCount_);
          }};
}

PassDecl Denoiser::temporalPass(const Colour& out) {
  return {"temporal",
          {"noisy", "guide", "gbuffer.visibility", "gbuffer.normal", "gbuffer.material",
           "gbuffer.motion", "gbuffer.depth", "prev.geometry", "prev.aux", "prev.moments",
           "prev.history"},
          colourWrites(out.name, out.at == Lobes::History, {"geometry", "aux", "moments"}),
          [this, at = out.at] {
            const std::array<GLuint, 2> o = lobes(at);
            temporal(frameIn_.g, o[0], o[1]);
            stages_[0][0] = o[0];
            stages_[0][1] = o[1];
          }};
}

PassDecl Denoiser::fireflyPass(const Colour& in, const Colour& out) {
  return {"firefly",
          {in.name, "geometry"},
          colourWrites(out.name, out.at == Lobes::History),
          [this, from = in.at, to = out.at] { firefly(lobes(from).data(), lobes(to).data()); }};
}

PassDecl Denoiser::atrousPass(int iteration, bool last, const Colour& in, const Colour& out) {
  std::vector<std::string> reads = {in.name, "geometry", "aux", "guide"};  // guide: where marked
  if (last) reads.insert(reads.end(), {"albedo", "unfiltered"});
  const std::vector<std::string> composited =
      last ? std::vector<std::string>{"composited"} : std::vector<std::string>{};
  return {last ? "atrous+composite" : "atrous", reads,
          colourWrites(out.name, out.at == Lobes::History, composited),
          [this, iteration, from = in.at, to = out.at] {
            const std::array<GLuint, 2> o = lobes(to);
            atrous(iteration, lobes(from).data(), o.data());
            stages_[iteration + 1][0] = o[0];
            stages_[iteration + 1][1] = o[1];
          }};
}

PassDecl Denoiser::compositePass(const Colour& in) {
  return {"composite",
          {in.name, "albedo", "unfiltered", "gbuffer.depth"},
          {"linear", "display", "depth"},
          [this, from = in.at] { composite(lobes(from).data(), frameIn_.g); }};
}

PassDecl Denoiser::resolvePass() {
  return {"resolve",
          {"composited", "prev.resolveHistory", "gbuffer.motion", "gbuffer.depth"},
          {"resolveHistory", "linear", "display", "depth"},
          [this] { resolve(frameIn_.g); }};
}

std::array<GLuint, 2> Denoiser::lobes(Lobes at) const {
  const int cur = frame_ & 1;
  switch (at) {
    case Lobes::Noisy:
      return {inputs_[InDiffuse], inputs_[InSpecular]};
    case Lobes::History:
      return {history_[cur][0], history_[cur][1]};
    case Lobes::PrevHistory:
      return {history_[cur ^ 1][0], history_[cur ^ 1][1]};
    case Lobes::FilterA:
      return {filterA_[0], filterA_[1]};
    case Lobes::FilterB:
      return {filterB_[0], filterB_[1]};
  }
  assert(false && "unknown Lobes");
  return {};
}

// ---------------------------------------------------------------------------------------
// The passes' GL work

void Denoiser::upload(const std::array<NoisyEye, 2>& eyes, int eyeCount) {
  api::PixelStorei(GL_UNPACK_ALIGNMENT, 4);
  for (int e = 0; e < eyeCount; ++e) {
    const NoisyEye& n = eyes[e];
    if (n.width != width_ || n.height != height_)
      throw UsageError("denoiser: eye " + std::to_string(e) + " is " + std::to_string(n.width) +
                       "x" + std::to_string(n.height) + ", expected " + std::to_string(width_) +
                       "x" + std::to_string(height_));
    const glm::vec3* data[InCount] = {n.diffuse,        n.specular,   n.diffuseAlbedo,
                                      n.specularAlbedo, n.unfiltered, n.guide};
    for (int i = 0; i < InCount; ++i) {
      if (i == InGuide && !data[i]) {
        api::ClearTexSubImage(inputs_[i], 0, 0, 0, e, width_, height_, 1, GL_RGB, GL_FLOAT,
                              nullptr);
        continue;
      }
      if (!data[i])
        throw UsageError("denoiser: an input image of eye " + std::to_string(e) + " is missing");
      api::TextureSubImage3D(inputs_[i], 0, 0, 0, e, width_, height_, 1, GL_RGB, GL_FLOAT, data[i]);
    }
  }
}

void Denoiser::uploadUniforms(bool reset) {
  const DenoiseParams& p = params_;
  shared::DenoiseUniforms u{};
  u.temporal = {p.colorAlpha, p.momentsAlpha, float(p.historyCap), float(p.temporalVarianceFrames)};
  u.reject = {p.depthRejectFactor, p.depthRejectEpsilon, p.normalRejectDistance,
              p.requireSameTriangle ? 1.0f : 0.0f};
  u.edge = {p.sigmaDepth, p.sigmaNormal, p.sigmaLuminance, p.sigmaLuminanceSpecular};
  u.display = {p.exposure, p.specularFootprint, p.specularMaxStep, 0.0f};
  u.tuning = {p.normalRejectSlope, p.resolveAlpha, float(p.resolveHistoryCap), p.fireflyFactor};
  u.frame = {width_, height_, reset ? 1 : 0, 0};
  api::NamedBufferSubData(uniforms_, 0, sizeof(u), &u);
  api::BindBufferBase(GL_UNIFORM_BUFFER, SVGF_UNIFORMS_BINDING, uniforms_);
}

void Denoiser::dispatch() const {
  const GLuint gx = GLuint((width_ + SVGF_GROUP - 1) / SVGF_GROUP);
  const GLuint gy = GLuint((height_ + SVGF_GROUP - 1) / SVGF_GROUP);
  api::DispatchCompute(gx, gy, GLuint(eyeCount_));
  passBarrier();
}

void Denoiser::temporal(const DenoiseGeometry& g, unsigned outDiffuse, unsigned outSpecular) {
  const int cur = frame_ & 1, prev = cur ^ 1;
  temporal_.use();
  api::BindTextureUnit(SVGF_T_IN_DIFFUSE, inputs_[InDiffuse]);
  api::BindTextureUnit(SVGF_T_IN_SPECULAR, inputs_[InSpecular]);
  api::BindTextureUnit(SVGF_T_VISIBILITY, g.visibility);
  api::BindTextureUnit(SVGF_T_NORMAL, g.normal);
  api::BindTextureUnit(SVGF_T_MATERIAL, g.material);
  api::BindTextureUnit(SVGF_T_MOTION, g.motion);
  api::BindTextureUnit(SVGF_T_DEPTH, g.depth);
  api::BindTextureUnit(SVGF_T_PREV_GEOMETRY, geometry_[prev]);
  api::BindTextureUnit(SVGF_T_PREV_AUX, aux_[prev]);
  api::BindTextureUnit(SVGF_T_PREV_MOMENTS, moments_[prev]);
  api::BindTextureUnit(SVGF_T_GUIDE, inputs_[InGuide]);
  api::BindTextureUnit(SVGF_T_PREV_DIFFUSE, history_[prev][0]);
  api::BindTextureUnit(SVGF_T_PREV_SPECULAR, history_[prev][1]);
  bindImage(SVGF_I_DIFFUSE, outDiffuse, GL_RGBA16F);
  bindImage(SVGF_I_SPECULAR, outSpecular, GL_RGBA16F);
  bindImage(SVGF_I_GEOMETRY, geometry_[cur], GL_RGBA32UI);
  bindImage(SVGF_I_AUX, aux_[cur], GL_RGBA16F);
  bindImage(SVGF_I_MOMENTS, moments_[cur], GL_RGBA32F);
  dispatch();
}

void Denoiser::bindCompositeInputs() const {
  api::BindTextureUnit(SVGF_C_DIFFUSE_ALBEDO, inputs_[InDiffuseAlbedo]);
  api::BindTextureUnit(SVGF_C_SPECULAR_ALBEDO, inputs_[InSpecularAlbedo]);
  api::BindTextureUnit(SVGF_C_UNFILTERED, inputs_[InUnfiltered]);
}

void Denoiser::bindOutputs(const DenoiseGeometry& g) const {
  api::BindTextureUnit(SVGF_C_DEPTH, g.depth);
  bindImage(SVGF_I_LINEAR, linear_, GL_RGBA16F);
  bindImage(SVGF_I_DISPLAY, display_, GL_RGBA8);
  bindImage(SVGF_I_DEPTH, depth_, GL_R32F);
}

void Denoiser::firefly(const unsigned in[2], const unsigned out[2]) {
  firefly_.use();
  api::BindTextureUnit(SVGF_A_DIFFUSE, in[0]);
  api::BindTextureUnit(SVGF_A_SPECULAR, in[1]);
  api::BindTextureUnit(SVGF_A_GEOMETRY, geometry_[frame_ & 1]);
  bindImage(SVGF_I_DIFFUSE, out[0], GL_RGBA16F);
  bindImage(SVGF_I_SPECULAR, out[1], GL_RGBA16F);
  dispatch();
}

namespace {

bool guided(const std::array<NoisyEye, 2>& eyes, int eyeCount) {
  for (int e = 0; e < eyeCount; ++e)
    if (eyes[e].guide) return true;
  return false;
}

}  // namespace

const Program& Denoiser::atrousProgram(bool specular, bool composite, bool guides) {
  if (!guides)
    return specular ? (composite ? atrousComposite_ : atrous_)
                    : (composite ? atrousDiffuseComposite_ : atrousDiffuse_);
  std::unique_ptr<Program>& p = atrousGuided_[specular][composite];
  if (!p) {
    std::vector<std::string> defines = {"SVGF_GUIDES 1"};
    if (!specular) defines.push_back("SVGF_SPECULAR_DONE 1");
    if (composite) defines.insert(defines.end(), {"SVGF_COMPOSITE 1", "SVGF_RESOLVE_FOLLOWS 1"});
    p = std::make_unique<Program>(
        std::vector<Program::Stage>{{GL_COMPUTE_SHADER, "svgf_atrous.comp"}}, defines);
  }
  return *p;
}

void Denoiser::atrous(int iteration, const unsigned in[2], const unsigned out[2]) {
  const bool last = iteration + 1 == params_.iterations;
  // Past max(1, cap) steps no pixel's lobe footprint reaches (svgf_atrous.comp).
  const bool specular = float(1 << iteration) <= std::max(1.0f, params_.specularMaxStep);
  const Program& program = atrousProgram(specular, last, guided(*frameIn_.eyes, eyeCount_));
  program.use();
  program.set("uStep", 1 << iteration);
  api::BindTextureUnit(SVGF_A_DIFFUSE, in[0]);
  api::BindTextureUnit(SVGF_A_SPECULAR, in[1]);
  api::BindTextureUnit(SVGF_A_GEOMETRY, geometry_[frame_ & 1]);
  api::BindTextureUnit(SVGF_A_AUX, aux_[frame_ & 1]);
  api::BindTextureUnit(SVGF_A_GUIDE, inputs_[InGuide]);
  bindImage(SVGF_I_DIFFUSE, out[0], GL_RGBA16F);
  bindImage(SVGF_I_SPECULAR, out[1], GL_RGBA16F);
  if (last) {
    bindCompositeInputs();
    bindImage(SVGF_I_LINEAR, composited_, GL_RGBA16F);
  }
  dispatch();
}

void Denoiser::resolve(const DenoiseGeometry& g) {
  const int cur = frame_ & 1;
  resolve_.use();
  api::BindTextureUnit(SVGF_R_COLOR, composited_);
  api::BindTextureUnit(SVGF_R_HISTORY, resolveHistory_[cur ^ 1]);
  api::BindTextureUnit(SVGF_R_MOTION, g.motion);
  bindImage(SVGF_I_HISTORY, resolveHistory_[cur], GL_RGBA16F);
  bindOutputs(g);
  dispatch();
}

void Denoiser::composite(const unsigned in[2], const DenoiseGeometry& g) {
  composite_.use();
  api::BindTextureUnit(SVGF_A_DIFFUSE, in[0]);
  api::BindTextureUnit(SVGF_A_SPECULAR, in[1]);
  bindCompositeInputs();
  bindOutputs(g);
  dispatch();
}

std::vector<glm::u8vec4> Denoiser::readDisplay(int eye) const {
  return readLayer<glm::u8vec4>(display_, GL_RGBA, GL_UNSIGNED_BYTE, width_, height_, eye);
}

std::vector<glm::vec3> Denoiser::readLinear(int eye) const {
  api::PixelStorei(GL_PACK_ALIGNMENT, 4);
  return readLayer<glm::vec3>(linear_, GL_RGB, GL_FLOAT, width_, height_, eye);
}

std::vector<float> Denoiser::readDepth(int eye) const {
  return readLayer<float>(depth_, GL_RED, GL_FLOAT, width_, height_, eye);
}

std::vector<glm::vec4> Denoiser::readStage(int stage, bool specular, int eye) const {
  assert(stage >= 0 && stage <= kMaxIterations);
  return readLayer<glm::vec4>(stages_[stage][specular ? 1 : 0], GL_RGBA, GL_FLOAT, width_, height_,
                              eye);
}

std::vector<glm::vec4> Denoiser::readMoments(int eye) const {
  return readLayer<glm::vec4>(moments_[(frame_ - 1) & 1], GL_RGBA, GL_FLOAT, width_, height_, eye);
}

std::vector<glm::vec4> Denoiser::readAux(int eye) const {
  return readLayer<glm::vec4>(aux_[(frame_ - 1) & 1], GL_RGBA, GL_FLOAT, width_, height_, eye);
}

std::vector<glm::vec4> Denoiser::readComposited(int eye) const {
  return readLayer<glm::vec4>(composited_, GL_RGBA, GL_FLOAT, width_, height_, eye);
}

std::vector<glm::vec4> Denoiser::readResolveHistory(int eye) const {
  return readLayer<glm::vec4>(resolveHistory_[(frame_ - 1) & 1], GL_RGBA, GL_FLOAT, width_, height_,
                              eye);
}

}  // namespace photovr::gl
