#include "gl/timewarp.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/error.h"
#include "gl/gl_api.h"
#include "gl/textures.h"
#include "shaders/compositor_shared.h"

namespace photovr::gl {
namespace {

static_assert(sizeof(shared::TimewarpEye) == 64 + 5 * 16, "std140 TimewarpEye");
static_assert(sizeof(shared::TimewarpUniforms) == 2 * sizeof(shared::TimewarpEye) + 3 * 16,
              "std140 TimewarpUniforms");

GLuint groups(int n, int group) {
  return GLuint((n + group - 1) / group);
}

// 1 / A-distance beyond which a point lies behind B's eye plane (B's origin c, in A's eye
// space, in front of A by -c.z): the search never looks past it.
float largestUsableRho(float cz) {
  return cz < 0.0f ? 0.999f / -cz : std::numeric_limits<float>::max();
}

shared::TimewarpEye eyeUniforms(const EyeCamera& a, const EyeCamera& b, const FovTangents& field) {
  shared::TimewarpEye w{};
  w.bToA = a.view() * b.pose.toWorld();
  w.aFov = {a.fov.left, a.fov.right, a.fov.up, a.fov.down};
  w.aPixel = {a.jitter.x, a.jitter.y, a.znear, b.znear};
  w.bFov = {b.fov.left, b.fov.right, b.fov.up, b.fov.down};
  w.bPixel = {b.jitter.x, b.jitter.y, largestUsableRho(w.bToA[3].z), 0.0f};
  w.bField = {field.left, field.right, field.up, field.down};
  return w;
}

}  // namespace

Timewarp::Timewarp(const LensParams& lens, int eyeWidth, int eyeHeight,
                   const std::array<FovTangents, 2>& eyeFov, const TimewarpParams& params)
    : eyeWidth_(eyeWidth),
      eyeHeight_(eyeHeight),
      panelWidth_(lens.hResolution),
      panelHeight_(lens.vResolution),
      tiles_((eyeWidth + COMP_TW_TILE - 1) / COMP_TW_TILE,
             (eyeHeight + COMP_TW_TILE - 1) / COMP_TW_TILE),
      params_(params),
      panelProgram_({{GL_COMPUTE_SHADER, "timewarp.comp"}}, {"TIMEWARP_PANEL"}),
      asRenderedProgram_({{GL_COMPUTE_SHADER, "timewarp.comp"}},
                         {"TIMEWARP_PANEL", "TIMEWARP_AS_RENDERED"}),
      eyeProgram_({{GL_COMPUTE_SHADER, "timewarp.comp"}}, {}),
      tileProgram_({{GL_COMPUTE_SHADER, "timewarp_tiles.comp"}}, {}) {
  if (eyeWidth < 1 || eyeHeight < 1) throw UsageError("timewarp: empty eye buffer");
  if (lens.hResolution < 2 || lens.hResolution % 2 || lens.vResolution < 1)
    throw UsageError("timewarp: the panel needs an even width and a height");
  uniforms_ = makeDynamicBuffer(sizeof(shared::TimewarpUniforms));
  stats_ = makeDynamicBuffer(8 * sizeof(uint32_t));
  linearSampler_ = makeLinearSampler();
  tileRange_ = makeArrayTexture(GL_RG32F, tiles_.x, tiles_.y, 2);
  tileBound_ = makeArrayTexture(GL_RG32F, tiles_.x, tiles_.y, 2);
  eyeColor_ = makeArrayTexture(GL_RGBA16F, eyeWidth, eyeHeight, 2);
  eyeDepth_ = makeArrayTexture(GL_R32F, eyeWidth, eyeHeight, 2);
  buildLensTable(lens, eyeFov);
  buildPasses();
}

Timewarp::~Timewarp() {
  const GLuint t[] = {lensTable_, tileRange_, tileBound_, eyeColor_, eyeDepth_};
  api::DeleteTextures(5, t);
  const GLuint b[] = {uniforms_, stats_, lensGroups_};
  api::DeleteBuffers(lensGroups_ ? 3 : 2, b);
  api::DeleteSamplers(1, &linearSampler_);
}

void Timewarp::buildLensTable(const LensParams& lens, const std::array<FovTangents, 2>& eyeFov) {
  lensTable_ = makeTexture2D(GL_RGBA32F, panelWidth_, panelHeight_);
  const Program lut({{GL_COMPUTE_SHADER, "timewarp_lut.comp"}}, {});
  const GLuint buffer = makeDynamicBuffer(sizeof(shared::DistortUniforms));
  lut.use();
  api::BindImageTexture(COMP_TW_I_OUT, lensTable_, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  for (int e = 0; e < 2; ++e) {
    const shared::DistortUniforms u =
        distortUniforms(lens, e, eyeFov[e], eyeWidth_, eyeHeight_, false);
    api::NamedBufferSubData(buffer, 0, sizeof(u), &u);
    api::BindBufferBase(GL_UNIFORM_BUFFER, COMP_DISTORT_BINDING, buffer);
    api::DispatchCompute(groups(panelWidth_ / 2, COMP_GROUP), groups(panelHeight_, COMP_GROUP), 1);
  }
  api::MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
  api::DeleteBuffers(1, &buffer);
  // The pixels each eye's lens shows: the panel mode's count of the outputs it sorts, and
  // the groups it computes.
  const std::vector<float> redScale =
      readTextureLayer<float>(lensTable_, GL_BLUE, GL_FLOAT, panelWidth_, panelHeight_, 0);
  lensSees_.resize(redScale.size());
  for (size_t i = 0; i < redScale.size(); ++i) {
    lensSees_[i] = redScale[i] > 0.0f;
    if (lensSees_[i]) ++lensVisible_[int(i % size_t(panelWidth_)) >= panelWidth_ / 2];
  }
}

bool Timewarp::groupSees(int rotation, int outWidth, int outHeight, int gx, int gy) const {
  const int g = COMP_TW_GROUP;
  for (int y = gy * g; y < std::min((gy + 1) * g, outHeight); ++y)
    for (int x = gx * g; x < std::min((gx + 1) * g, outWidth); ++x) {
      const glm::ivec2 p = panelSourceTexel(rotation, panelWidth_, panelHeight_, x, y);
      if (lensSees_[size_t(p.y) * size_t(panelWidth_) + size_t(p.x)]) return true;
    }
  return false;
}

void Timewarp::buildLensGroups(const PanelOutput& out) {
  std::vector<uint32_t> list;
  const int g = COMP_TW_GROUP;
  for (int gy = 0; gy * g < out.height(); ++gy)
    for (int gx = 0; gx * g < out.width(); ++gx)
      if (groupSees(out.rotation(), out.width(), out.height(), gx, gy))
        list.push_back(uint32_t(gx) | uint32_t(gy) << 16);
  if (lensGroups_ != 0) api::DeleteBuffers(1, &lensGroups_);
  api::CreateBuffers(1, &lensGroups_);
  api::NamedBufferStorage(lensGroups_, GLsizeiptr(std::max<size_t>(list.size(), 1) * 4),
                          list.empty() ? nullptr : list.data(), 0);
  lensGroupCount_ = int(list.size());
  lensGroupRotation_ = out.rotation();
}

void Timewarp::setUniforms(const std::array<EyeCamera, 2>& from, const std::array<EyeCamera, 2>& to,
                           int eyeCount, float exposure, int rotation) {
  if (eyeCount < 1 || eyeCount > 2) throw UsageError("timewarp: eye count must be 1 or 2");
  for (int e = 0; e < eyeCount; ++e)
    if (from[e].width != eyeWidth_ || from[e].height != eyeHeight_ || to[e].width != eyeWidth_ ||
        to[e].height != eyeHeight_)
      throw UsageError("timewarp: cameras of eye " + std::to_string(e) + " are not " +
                       std::to_string(eyeWidth_) + "x" + std::to_string(eyeHeight_));
  shared::TimewarpUniforms u{};
  for (int e = 0; e < eyeCount; ++e)
    u.eye[e] = eyeUniforms(from[e], to[e], field_ ? (*field_)[size_t(e)] : to[e].fov);
  u.params = {params_.depthRatio, params_.stepPixels, float(params_.maxSteps), exposure};
  u.size = {eyeWidth_, eyeHeight_, panelWidth_, panelHeight_};
  u.mode = {0, rotation, tiles_.x, tiles_.y};
  api::NamedBufferSubData(uniforms_, 0, sizeof(u), &u);
  api::BindBufferBase(GL_UNIFORM_BUFFER, COMP_TW_BINDING, uniforms_);
  const GLuint zero = 0;
  api::ClearNamedBufferData(stats_, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  api::BindBufferBase(GL_SHADER_STORAGE_BUFFER, COMP_TW_STATS, stats_);
}

// ---------------------------------------------------------------------------------------
// The pass lists: the search bounds (tile minima and maxima of A's depth, then their 3x3
// extremes) before the passes that search.

void Timewarp::buildPasses() {
  const std::vector<std::string> in = {"color", "depth", "lensTable", "lensGroups"};
  passes_[size_t(TimewarpRun::Panel)] =
      PassList(in, {"panel", "stats"}, {tilePass(0), tilePass(1), panelPass(TimewarpRun::Panel)});
  passes_[size_t(TimewarpRun::PanelAsRendered)] =
      PassList(in, {"panel", "stats"}, {panelPass(TimewarpRun::PanelAsRendered)});
  passes_[size_t(TimewarpRun::PanelFloor)] =
      PassList(in, {"panel"}, {panelPass(TimewarpRun::PanelFloor)});
  passes_[size_t(TimewarpRun::Eyes)] = PassList(
      {"color", "depth"}, {"eyeColor", "eyeDepth", "stats"}, {tilePass(0), tilePass(1), eyePass()});
}

PassDecl Timewarp::tilePass(int pass) {
  if (pass == 0) return {"tileRange", {"depth"}, {"tileRange"}, [this] { runTiles(0); }};
  return {"tileBound", {"tileRange"}, {"tileBound"}, [this] { runTiles(1); }};
}

PassDecl Timewarp::panelPass(TimewarpRun run) {
  if (run == TimewarpRun::PanelAsRendered)  // the frame's depth unread
    return {"panelAsRendered", {"color", "lensTable", "lensGroups"}, {"panel", "stats"}, [this] {
              bindColor(frameIn_.color);
              drawPanel(asRenderedProgram_, *frameIn_.out);
            }};
  if (run == TimewarpRun::PanelFloor)  // no search, no origins counted
    return {"panelFloor", {"color", "depth", "lensTable", "lensGroups"}, {"panel"}, [this] {
              api::BindTextureUnit(COMP_TW_DEPTH, frameIn_.depth);
              bindColor(frameIn_.color);
              drawPanel(*floorProgram_, *frameIn_.out);
            }};
  return {"panel",
          {"color", "depth", "tileBound", "lensTable", "lensGroups"},
          {"panel", "stats"},
          [this] {
            bindSearch(frameIn_.depth);
            bindColor(frameIn_.color);
            drawPanel(panelProgram_, *frameIn_.out);
          }};
}

PassDecl Timewarp::eyePass() {
  return {"eyes", {"color", "depth", "tileBound"}, {"eyeColor", "eyeDepth", "stats"}, [this] {
            bindSearch(frameIn_.depth);
            bindColor(frameIn_.color);
            drawEyes(frameIn_.eyeCount);
          }};
}

void Timewarp::checkSearch(const std::array<EyeCamera, 2>& from, int eyeCount) const {
  for (int e = 0; e < eyeCount; ++e)
    if (from[e].zfar != 0.0f) throw UsageError("timewarp: pose A needs infinite reversed-Z");
  if (!(params_.stepPixels > 0.0f) || params_.maxSteps < 1 || params_.maxSteps > 1024)
    throw UsageError("timewarp: step must be positive and max steps in [1, 1024]");
}

// Pass 0: per-tile depth range of A's depth; pass 1: its 3x3 extremes.
void Timewarp::runTiles(int pass) {
  tileProgram_.use();
  api::BindSampler(COMP_TW_DEPTH, linearSampler_);  // clamp to edge for the tiles' gathers
  tileProgram_.set("uPass", pass);
  api::BindTextureUnit(COMP_TW_DEPTH, pass == 0 ? frameIn_.depth : tileRange_);
  api::BindImageTexture(COMP_TW_I_TILES, pass == 0 ? tileRange_ : tileBound_, 0, GL_TRUE, 0,
                        GL_WRITE_ONLY, GL_RG32F);
  api::DispatchCompute(groups(tiles_.x, COMP_TW_GROUP), groups(tiles_.y, COMP_TW_GROUP),
                       GLuint(frameIn_.eyeCount));
  api::MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
}

void Timewarp::bindSearch(unsigned depthArray) {
  api::BindTextureUnit(COMP_TW_DEPTH, depthArray);
  api::BindSampler(COMP_TW_DEPTH, linearSampler_);  // for textureGather's clamp to edge
  api::BindTextureUnit(COMP_TW_TILES, tileBound_);
}

void Timewarp::bindColor(unsigned colorArray) {
  api::BindTextureUnit(COMP_TW_COLOR, colorArray);
  api::BindSampler(COMP_TW_COLOR, linearSampler_);
}

void Timewarp::unbindSamplers() {
  api::BindSampler(COMP_TW_COLOR, 0);
  api::BindSampler(COMP_TW_DEPTH, 0);
}

void Timewarp::runPanel(unsigned colorArray, unsigned depthArray,
                        const std::array<EyeCamera, 2>& from, const std::array<EyeCamera, 2>& to,
                        float exposure, PanelOutput& out) {
  checkPanel(out);
  setUniforms(from, to, 2, exposure, out.rotation());
  checkSearch(from, 2);
  frameIn_ = {colorArray, depthArray, &out, 2};
  passes_[size_t(TimewarpRun::Panel)].run();
}

void Timewarp::runPanelFloor(unsigned colorArray, unsigned depthArray,
                             const std::array<EyeCamera, 2>& at, PanelOutput& out) {
  if (!floorProgram_)
    floorProgram_ = std::make_unique<Program>(
        std::vector<Program::Stage>{{GL_COMPUTE_SHADER, "timewarp_floor.comp"}},
        std::vector<std::string>{});
  checkPanel(out);
  setUniforms(at, at, 2, 1.0f, out.rotation());
  frameIn_ = {colorArray, depthArray, &out, 2};
  passes_[size_t(TimewarpRun::PanelFloor)].run();
}

void Timewarp::runPanelAsRendered(unsigned colorArray, const std::array<EyeCamera, 2>& at,
                                  float exposure, PanelOutput& out) {
  checkPanel(out);
  setUniforms(at, at, 2, exposure, out.rotation());
  frameIn_ = {colorArray, 0, &out, 2};
  passes_[size_t(TimewarpRun::PanelAsRendered)].run();
}

void Timewarp::checkPanel(const PanelOutput& out) {
  if (out.panelWidth() != panelWidth_ || out.panelHeight() != panelHeight_)
    throw UsageError("timewarp: the panel output is not " + std::to_string(panelWidth_) + "x" +
                     std::to_string(panelHeight_));
  if (out.rotation() != lensGroupRotation_) buildLensGroups(out);
}

void Timewarp::drawPanel(const Program& program, PanelOutput& out) {
  counted_ = lensVisible_;
  const float black[4] = {0.0f, 0.0f, 0.0f, 1.0f};
  api::ClearTexImage(out.texture(), 0, GL_RGBA, GL_FLOAT, black);
  program.use();
  api::BindTextureUnit(COMP_TW_LUT, lensTable_);
  api::BindImageTexture(COMP_TW_I_OUT, out.texture(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);
  api::BindBufferBase(GL_SHADER_STORAGE_BUFFER, COMP_TW_GROUPS, lensGroups_);
  if (lensGroupCount_ > 0) api::DispatchCompute(GLuint(lensGroupCount_), 1, 1);
  api::MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT |
                     GL_FRAMEBUFFER_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT |
                     GL_BUFFER_UPDATE_BARRIER_BIT);
  unbindSamplers();
}

void Timewarp::drawEyes(int eyeCount) {
  counted_ = {eyeWidth_ * eyeHeight_, eyeCount > 1 ? eyeWidth_ * eyeHeight_ : 0};
  eyeProgram_.use();
  api::BindImageTexture(COMP_TW_I_OUT, eyeColor_, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
  api::BindImageTexture(COMP_TW_I_DEPTH, eyeDepth_, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R32F);
  api::DispatchCompute(groups(eyeWidth_, COMP_TW_GROUP), groups(eyeHeight_, COMP_TW_GROUP),
                       GLuint(eyeCount));
  api::MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT |
                     GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  unbindSamplers();
}

void Timewarp::runEyes(unsigned colorArray, unsigned depthArray,
                       const std::array<EyeCamera, 2>& from, const std::array<EyeCamera, 2>& to,
                       int eyeCount) {
  setUniforms(from, to, eyeCount, 1.0f, 0);
  checkSearch(from, eyeCount);
  frameIn_ = {colorArray, depthArray, nullptr, eyeCount};
  passes_[size_t(TimewarpRun::Eyes)].run();
}

std::vector<glm::vec4> Timewarp::readColor(int eye) const {
  return readTextureLayer<glm::vec4>(eyeColor_, GL_RGBA, GL_FLOAT, eyeWidth_, eyeHeight_, eye);
}

std::vector<float> Timewarp::readDepth(int eye) const {
  return readTextureLayer<float>(eyeDepth_, GL_RED, GL_FLOAT, eyeWidth_, eyeHeight_, eye);
}

ReprojectStats Timewarp::stats(int eye) const {
  if (eye < 0 || eye > 1) throw UsageError("timewarp: eye must be 0 or 1");
  api::MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  uint32_t counts[8] = {};
  api::GetNamedBufferSubData(stats_, 0, sizeof counts, counts);
  const uint32_t* c = counts + 4 * eye;  // uncovered, filled (timewarp.comp countOrigin)
  return {counted_[size_t(eye)] - int(c[0]) - int(c[1]), int(c[1]), int(c[0])};
}

}  // namespace photovr::gl
