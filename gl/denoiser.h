// Spatiotemporal variance-guided denoiser and compositor (issue 5; Schied et al.,
// "Spatiotemporal Variance-Guided Filtering", HPG 2017 — "SVGF" below, sections and
// equation numbers refer to it). Both eyes are processed together: every pass is one
// compute dispatch over 2-layer array textures, layer = eye, each eye with its own history.
//
// Passes (all compute, 8x8 groups; see shaders/svgf_*.comp for what each reads/writes):
//   upload     5 x RGB32F      noisy diffuse, noisy specular (both demodulated), albedos,
//                              unfiltered radiance (32-bit: a plain copy, no conversion)
//   temporal   -> RGBA16F x 2  accumulated colour, alpha = luminance variance (SVGF §4.1-4.2)
//                 RGBA32UI     geometry record (instance, triangle, depth, normal)
//                 RGBA16F      history length, depth gradient / depth, roughness
//                 RGBA32F      luminance moments (mu1, mu2) of diffuse and specular
//   firefly    -> RGBA16F x 2  accumulated colour, clamped to the 3x3 neighbours' maximum;
//                              next frame's colour history (not iteration 0's output, as
//                              in SVGF §4.3: DenoiseParams::historyFromFirstIteration)
//   a-trous i  -> RGBA16F x 2  filtered colour + variance, step 2^i (SVGF §4.3-4.4)
//   composite  -> RGBA16F      linear colour (for the headset compositor)
//                 RGBA8        display colour: exposure, PBR Neutral, sRGB-encoded
//                 R32F         reversed-Z depth (the G-buffer's is overwritten next frame)
//   resolve    -> RGBA16F      temporal anti-aliasing of the composite (Karis 2014), its
//                              history (colour, sample count); writes the composite's outputs
// 'full' fuses the composite into the last a-trous iteration and resolves it; 'temporal'
// and 'off' run the composite alone (on the temporal output, resp. the raw input).
// Each mode's passes are one PassList (gl/pass_list.h), declared in denoiser.cpp's
// buildPasses with the resources each reads and writes, and rebuilt when the parameters
// change; passes(mode) shows them.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "gl/pass_list.h"
#include "gl/program.h"

namespace photovr::gl {

class GBufferPass;

enum class DenoiseMode { Off, Temporal, Full };
DenoiseMode parseDenoiseMode(const std::string& name);  // "off|temporal|full"; else UsageError
std::string denoiseModeName(DenoiseMode mode);

// Every tunable of the denoiser with its source.
struct DenoiseParams {
  // SVGF §4.1: exponential moving average weight of the new sample, colour ...
  float colorAlpha = 0.2f;
  // ... and luminance moments (§4.2, the same 0.2).
  float momentsAlpha = 0.2f;
  // History length cap; with alpha = max(alpha, 1/n) only n < 1/alpha matters, the cap
  // just bounds the stored count (Falcor SVGFReproject uses 32).
  int historyCap = 32;
  // SVGF §4.2: below 4 frames of history the variance is estimated spatially (7x7).
  int temporalVarianceFrames = 4;
  // Back-projection rejection (SVGF §4.1 names the tests; thresholds from Falcor's
  // SVGFReproject): depth change > 10 x (|grad z| + epsilon); normals further apart than
  // 16 x 1e-2. The epsilon is relative here (Falcor: 1e-2 in scene units): 0.5 % of the
  // distance admits the depth change of a head moving 1 m/s at 75 Hz at 2.7 m.
  float depthRejectFactor = 10.0f;
  float depthRejectEpsilon = 5e-3f;
  float normalRejectDistance = 0.16f;
  // ... plus 16 x the normal's screen-space variation |dn/dx| + |dn/dy| (Falcor's
  // "distance / (fwidth(n) + 1e-2) > 16"). Without it no pixel of the spheres scene's
  // small spheres kept history under the per-frame jitter (measured).
  float normalRejectSlope = 16.0f;
  // Also reject history from another triangle of the same instance (issue 5, item 1).
  // Off by default, measured: with the per-frame sub-pixel jitter, pixels of finely
  // tessellated meshes (the spheres' ~4-pixel triangles) change triangle every frame, so
  // the test threw away nearly all their history (denoised spheres relMSE 0.111 vs raw
  // 0.129). SVGF itself tests the mesh id only (sec. 4.1); depth and normal tests catch
  // real disocclusions within a mesh.
  bool requireSameTriangle = false;
  // SVGF §4.4 / §5: sigma_z = 1 (eq. 3), sigma_n = 128 (eq. 4), sigma_l = 4 (eq. 5). The
  // variance in eq. 5 is that of the temporally averaged colour the filter receives (one
  // sample's x sum w_k^2, svgf_temporal.comp), as eq. 2 propagates it, where SVGF uses one
  // sample's: with one sample's the spheres' contact shadows were smeared away (48x54,
  // relMSE 0.124 -> 0.079 with the change; cornell unchanged, atrium 0.227 -> 0.212).
  float sigmaDepth = 1.0f;
  float sigmaNormal = 128.0f;
  float sigmaLuminance = 4.0f;
  // Ours (no source in SVGF, which has no specular split): a tighter colour weight for
  // specular, whose edges are reflections that the geometry weights cannot see.
  float sigmaLuminanceSpecular = 2.0f;
  // Ours: specular is filtered while step <= max(1, min(maxStep, footprint x alpha)), alpha =
  // roughness^2: the GGX lobe's width (the half-angle holding 75 % of it has tangent 3 alpha,
  // Lagarde and de Rousiers 2014, "Moving Frostbite to PBR", p. 72, as NRD uses it).
  // 32 lets roughness 0.25 use steps 1-2, 0.35 and up 1-4, below 0.25 step 1 only. It was
  // 16 (roughness 0.25: step 1 only), which left cornell's glossy tall block (metal,
  // roughness 0.25, reflecting the red wall and the floor) speckled where the reference is
  // smooth. Measured (tests/hybrid/denoise_glossy_test.cpp: 96x108, 8 frames, 512-spp
  // reference, relMSE over the block's interior pixels, tracer seeds 0 and 2-5): 0.0096-0.0119
  // with (16, no cap), 0.0071-0.0077 with (32, 4); at 240x270, seed 0: 0.0119 -> 0.0072.
  // 64 (steps 1-4 at 0.25) took the block to 0.0062 at 240x270 but blurred the atrium's
  // narrow sky streak on its polished floor (roughness 0.3): atrium relMSE +0.1 to +1.2 %.
  float specularFootprint = 32.0f;
  // ... and never beyond step 4 (a reach of +-14 pixels): steps 8 and 16 only spread the
  // rough specular lobe across shadow edges (it carries the shadows as diffuse does, with
  // the larger relative noise of a small specular albedo). Measured with footprint 32, seeds
  // 0, 2, 3, 4, uncapped -> capped: spheres 0.01017-0.01194 -> 0.01011-0.01189 (under the
  // old 0.01014-0.01191), atrium 0.02925-0.03067 -> 0.02922-0.03064 (old 0.02968-0.03110);
  // cap 8 sat in between (seeds 0, 2).
  float specularMaxStep = 4.0f;
  // Before the a-trous filter, clamp each lobe's accumulated luminance to 'factor' x the
  // brightest of its 3x3 neighbours on the same surface (rank-conditioned rank selection
  // as NRD ReLAX's anti-firefly; shaders/svgf_firefly.comp). Factor 4, measured (96x108,
  // 8 frames, relMSE): 1 (plain RCRS) also darkened ordinary noise peaks, cornell 0.0111
  // -> 0.0207 and atrium 0.0205 -> 0.0423; 4 costs them 20 % / 3 % and takes spheres from
  // 0.0192 to 0.0152 (its metal spheres' fireflies are 10-100x their neighbours).
  bool suppressFireflies = true;
  float fireflyFactor = 4.0f;
  // SVGF §4.3 feeds the colour history with the first a-trous iteration's output; ours is
  // the temporal output after the firefly clamp. Fed back, the step-1 filter is applied
  // again every frame, and its small leak across an edge that the luminance weight does
  // not stop compounds over the history's ~1 / alpha = 5 frames. Measured on the spheres
  // scene (tests/hybrid, 96x108, 8 frames, tracer seeds 10-25): 76 % of the denoised
  // relMSE (0.0167) was the same in every seed, and 60 % came from the shadowed floor (8 %
  // of the pixels), the 1-2 pixel contact shadows under the spheres. One such pixel:
  // reference 0.107, raw frame 0.119 (mean over seeds), temporal pass alone 0.112, with
  // the 5 iterations 0.295, with only the first 0.252. The pixel beside it on the shadow's
  // edge, lit or not by turns under the jitter, has 25x its variance, and the 3x3 variance
  // prefilter (§4.4) widens the shadow pixel's luminance weight with it. With the temporal
  // output as history that pixel reads 0.218, the shadowed floor's share drops from 0.0100
  // to 0.0048 and spheres' relMSE from 0.0167 to 0.0111. Seeds 0, 2-4, this (default) vs
  // SVGF's: spheres 0.0101-0.0119 vs 0.0152-0.0172, cornell 0.0171-0.0180 vs
  // 0.0166-0.0178, atrium 0.0297-0.0311 vs 0.0274-0.0290 (the filtered history's lower
  // noise was worth 9 % there).
  // tests/hybrid/denoise_history_test.cpp shows the mechanism on a synthetic shadow.
  bool historyFromFirstIteration = false;
  // SVGF §4.3: 5 a-trous iterations (steps 1, 2, 4, 8, 16).
  int iterations = 5;
  // Resolve: temporal anti-aliasing of the re-modulated result, which ends SVGF's pipeline
  // (fig. 2; Karis 2014): blend weight of the new frame, 0.1 as Falcor's TAA pass and
  // Salvi 2016, a plain mean over the first 10 frames ...
  float resolveAlpha = 0.1f;
  // ... with the per-pixel sample count capped (only n < 1 / alpha matters).
  int resolveHistoryCap = 16;
  // Display transform: linear scale before the tone map.
  float exposure = 1.0f;
};

// One eye's denoiser input on the CPU: linear RGB, rows bottom-up as GL stores them,
// width x height each. Diffuse and specular radiance are demodulated by their albedos.
struct NoisyEye {
  int width = 0, height = 0;
  const glm::vec3* diffuse = nullptr;
  const glm::vec3* specular = nullptr;
  const glm::vec3* diffuseAlbedo = nullptr;
  const glm::vec3* specularAlbedo = nullptr;
  const glm::vec3* unfiltered = nullptr;  // primary emission; the sky in background pixels
  // Optional: primary surface replacement for the a-trous edge weights where a pixel looks
  // through a smooth mirror or glass (EyeImage::guide: the seen surface's normal scaled by
  // its instance + 1, 0 = the G-buffer's guides). Null: none anywhere (the a-trous pass
  // then runs without the guide's reads).
  const glm::vec3* guide = nullptr;
};

// The G-buffer textures the denoiser reads (2-layer arrays, formats as in gl/gbuffer.h).
struct DenoiseGeometry {
  unsigned visibility = 0, normal = 0, material = 0, motion = 0, depth = 0;
};
DenoiseGeometry denoiseGeometry(const GBufferPass& gbuffer);

class Denoiser {
 public:
  Denoiser(int eyeWidth, int eyeHeight, const DenoiseParams& params = {});
  ~Denoiser();
  Denoiser(const Denoiser&) = delete;
  Denoiser& operator=(const Denoiser&) = delete;

  // Denoises eyes [0, eyeCount) and composites them. History is dropped on resetHistory,
  // on the first frame, and after an 'off' frame (which does not maintain it).
  void run(const GBufferPass& gbuffer, const std::array<NoisyEye, 2>& eyes, int eyeCount,
           DenoiseMode mode, bool resetHistory);
  void run(const DenoiseGeometry& gbuffer, const std::array<NoisyEye, 2>& eyes, int eyeCount,
           DenoiseMode mode, bool resetHistory);

  std::vector<glm::u8vec4> readDisplay(int eye) const;  // sRGB-encoded, alpha 255
  std::vector<glm::vec3> readLinear(int eye) const;
  std::vector<float> readDepth(int eye) const;
  // Intermediate results of the last run, for tests and debugging. stage 0 = temporal
  // output, stage i + 1 = a-trous iteration i (ping-pong: intact for the last two stages).
  std::vector<glm::vec4> readStage(int stage, bool specular, int eye) const;
  std::vector<glm::vec4> readMoments(int eye) const;
  std::vector<glm::vec4> readAux(int eye) const;  // history length, grad depth / depth, roughness
  // The resolve's input (the composite of the filtered lobes) and its history (colour,
  // sample count) after the last 'full' run.
  std::vector<glm::vec4> readComposited(int eye) const;
  std::vector<glm::vec4> readResolveHistory(int eye) const;

  // For the headset compositor: 2-layer arrays, layer = eye.
  unsigned displayTexture() const { return display_; }  // RGBA8, sRGB-encoded values
  unsigned linearTexture() const { return linear_; }    // RGBA16F
  unsigned depthTexture() const { return depth_; }      // R32F reversed-Z

  void setParams(const DenoiseParams& params);  // and rebuilds the pass lists
  const DenoiseParams& params() const { return params_; }
  // Per-pass wall times of the last run (glFinish before and after each pass) when on.
  void setTiming(bool on) { timing_ = on; }
  const std::vector<PassTiming>& timings() const { return timings_; }
  int width() const { return width_; }
  int height() const { return height_; }
  // What run() runs in 'mode' under the current parameters, in order.
  const PassList& passes(DenoiseMode mode) const { return passes_[size_t(mode)]; }

 private:
  enum Input {
    InDiffuse,
    InSpecular,
    InDiffuseAlbedo,
    InSpecularAlbedo,
    InUnfiltered,
    InGuide,
    InCount
  };
  // Where a pair of lobe images (diffuse, specular) lives; History and PrevHistory by the
  // frame's parity.
  enum class Lobes { Noisy, History, PrevHistory, FilterA, FilterB };
  struct Colour {  // a lobe pair as the pass list names it, and where it lives
    std::string name;
    Lobes at;
  };
  struct FrameIn {  // run()'s arguments, for the passes
    DenoiseGeometry g;
    const std::array<NoisyEye, 2>* eyes = nullptr;
    bool reset = false;
  };
  void buildPasses();
  PassList buildPasses(DenoiseMode mode);
  void addFilterPasses(std::vector<PassDecl>& passes, Colour in, int iterations, bool clamp,
                       bool historyFiltered);
  PassDecl uploadPass();
  PassDecl temporalPass(const Colour& out);
  PassDecl fireflyPass(const Colour& in, const Colour& out);
  PassDecl atrousPass(int iteration, bool last, const Colour& in, const Colour& out);
  PassDecl compositePass(const Colour& in);
  PassDecl resolvePass();
  std::array<unsigned, 2> lobes(Lobes at) const;

  void upload(const std::array<NoisyEye, 2>& eyes, int eyeCount);
  void uploadUniforms(bool reset);
  void temporal(const DenoiseGeometry& g, unsigned outDiffuse, unsigned outSpecular);
  void firefly(const unsigned in[2], const unsigned out[2]);
  void atrous(int iteration, const unsigned in[2], const unsigned out[2]);
  void composite(const unsigned in[2], const DenoiseGeometry& g);
  void resolve(const DenoiseGeometry& g);
  void bindCompositeInputs() const;
  void bindOutputs(const DenoiseGeometry& g) const;
  void dispatch() const;

  int width_, height_;
  DenoiseParams params_;
  Program temporal_, firefly_, atrous_, atrousComposite_;
  Program atrousDiffuse_, atrousDiffuseComposite_;  // steps past the specular cap
  // The four with SVGF_GUIDES (frames with replaced guides), [specular][composite], built
  // when first needed: llvmpipe runs a branch's texture reads even where no pixel takes it,
  // which cost the a-trous steps 1.3x in frames without a replaced guide (measured).
  std::unique_ptr<Program> atrousGuided_[2][2];
  const Program& atrousProgram(bool specular, bool composite, bool guided);
  Program composite_, resolve_;
  unsigned uniforms_ = 0;
  unsigned inputs_[InCount] = {};
  // Ping-ponged by frame parity: [frame & 1] is written, the other read as "previous".
  unsigned geometry_[2] = {}, aux_[2] = {}, moments_[2] = {};
  unsigned history_[2][2] = {};                 // [parity][diffuse, specular]
  unsigned filterA_[2] = {}, filterB_[2] = {};  // [diffuse, specular]
  unsigned linear_ = 0, display_ = 0, depth_ = 0;
  unsigned composited_ = 0;          // the fused composite's linear colour, resolve input
  unsigned resolveHistory_[2] = {};  // [parity]
  unsigned stages_[6][2] = {};       // what readStage() reads
  int frame_ = 0;
  int eyeCount_ = 2;
  bool historyValid_ = false;
  bool timing_ = false;
  std::vector<PassTiming> timings_;
  FrameIn frameIn_;
  std::array<PassList, 3> passes_;  // by DenoiseMode
};

}  // namespace photovr::gl
