// Stereo path reuse (issue 21; the thesis's future work, sec. 4.2.2 "Ray/Path reprojection"):
// the right eye's sample at a surface the left eye also sees takes the left sample's path
// beyond the first hit instead of tracing its own. The eyes take turns (stereoTurnsOf): in
// this file "left" is the eye traced first, which records, and "right" the one that reuses.
//
// The shift keeps the direction (Lin et al., "Generalized Resampled Importance Sampling",
// SIGGRAPH 2022, sec. 5, calls it random replay; its Jacobian in solid angle is 1): the right
// sample at x1R (its own primary hit, shaded with its own material and view) takes the left
// sample's bounce direction w, drawn at x1L with pdf(w | x1L, woL), and the radiance L(w)
// the left path brought back along it. Its bounce term is
//
//   f(x1R, woR, w) |cos th1R| (w_bsdf(w) Le(x2) + L_beyond(x2)) / pdf(w | x1L, woL),
//
// an importance-sampled estimate of the right vertex's reflection integral over the
// directions the left pdf can draw, S_L (leftCovers). It is used on a region A of the
// directions only; the rest, B, is the right sample's own: it draws w' ~ pdf_R(w' | x1R,
// woR) with the left's BSDF numbers and, only if w' lies in B, traces its own path along it:
//
//   E[f |cos| L(w) / pdf_L(w) 1(w in A)] + E[f |cos| L(w') / pdf_R(w') 1(w' in B)]
//     = the integral over A + the integral over B = the whole integral,
//
// for any split with A inside S_L (a shift mapping's fallback for what it cannot map well).
// A is where pdf_R <= kReusePdfRatio g, g being the left pdf as the right vertex can
// estimate it (ReuseSplit; 0 outside S_L): there the reused weight f / pdf_L stays within
// ~kReusePdfRatio of the own sample's. B holds the wedge between two tilted hemispheres
// (curved surfaces, normal maps: without it the right vertex lost ~theta^2 / 4 of a
// Lambertian vertex's bounce light at normals theta apart), every direction where x1L's
// view is below its shading horizon, and the right lobe's part where the left pdf is thin:
// a glossy lobe on a curved surface, whose peak moves by twice the normals' angle; a lobe
// thinner than the views' angle (a mirror), whose peak the view change moves; the cosine lobe near
// the left's horizon, where cos_R / cos_L has no bound; a specular lobe the left picks less often
// (a texture edge). Without B those were fireflies the right eye's relMSE kept at 2048 frames
// (docs/MEASUREMENTS.md, "Stereo path reuse"). Le(x2), the emission the left ray found, is weighted
// against the right sample's own NEE with the power heuristic of the right vertex's own pdfs, so
// the two weights sum to one for every direction (unbiased MIS; Veach 1997 sec. 9.2). The right
// sample's NEE draws the left sample's numbers, so it aims at the left's light point (the light
// pick and the point on it depend on the numbers alone): from its own x1R, with its own BSDF,
// cosine and, for a light at a finite distance, its own distance and direction; its noise
// matches the left eye's.
//
// The approximations: the radiance arriving at x1R along w is taken as the radiance arriving
// at x1L along w, and where the left path traced its NEE shadow ray, that ray's answer stands
// for the right sample's (V(x1R, y) taken as V(x1L, y), y the light point). The two points lie
// within kPartnerPixels footprints of each other, so only what is about that close to the
// surface (contact, corners) or to a shadow's edge differs: the incident light is blurred by
// that distance, and a shadow's edge moves by at most that distance (as the left eye samples
// it) instead of being traced again, except at a punctual light's shadow edge, where the
// right sample traces its own (leftShadowEdge). Measured in tests/trace/stereo_reuse_test.cpp
// (per-region z-test against the right eye's own paths; a square light's penumbra on a wall,
// against every reused sample tracing its own shadow ray: every pixel beyond it the same to
// rounding, the penumbra moved by 0.4 pixels per row where the bound is 2.99) and
// bench/bench_stereo.cpp (the same comparison on every built-in scene: relMSE 3e-6 to 3e-4,
// 1 % of atrium's error at 32 frames). The shadow ray was a sixth of a reused sample's time
// on spheres (docs/MEASUREMENTS.md, "Stereo path reuse"). Reconnecting to x2 with the
// area-measure Jacobian instead (exact geometry at x1R) was tried: its Jacobian
// |cos th2R| |x2 - x1L|^2 / (|cos th2L| |x2 - x1R|^2) spikes where x2 is near x1 or seen at
// grazing angles, and the right eye's relMSE at equal time came out 1.08x better than off on
// cornell against 1.75x for this shift (docs/MEASUREMENTS.md, "Stereo path reuse").
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <type_traits>
#include <vector>

#include <glm/glm.hpp>

#include "core/camera.h"
#include "trace/bsdf.h"
#include "trace/lights.h"
#include "trace/rng.h"
#include "trace/sampling.h"
#include "trace/surface.h"
#include "trace/vertex_numbers.h"

namespace photovr {

// What the right eye needs of one left sample's path.
struct FirstBounce {
  static constexpr uint32_t kNone = ~0u;
  glm::vec3 position{0.0f}, normal{0.0f};  // x1L and its shading normal
  glm::vec3 geometricNormal{0.0f};         // ... its geometric normal
  glm::vec3 wo{0.0f};                      // ... and the left view (towards the left eye)
  uint32_t instance = kNone;               // x1L's instance; kNone: no path recorded
  bool sampled = false;  // the left path sampled a bounce at x1L (false: its indirect was 0)
  bool hit = false;      // ... whose ray found x2 (false: it left along 'dir')
  bool woAbove = false;  // x1L's view is above its shading horizon: it can sample at all
  float specularProbability = 0.0f;  // x1L's chance of sampling its specular lobe (BRDF)
  glm::vec3 dir{0.0f};               // the bounce direction at x1L
  float pdf = 0.0f;                  // its solid-angle pdf
  glm::vec3 x2{0.0f}, n2{0.0f};      // x2 and its geometric normal (the light pdf of Le(x2))
  uint32_t instance2 = 0, triangle2 = 0;
  glm::vec3 emitted{0.0f};      // Le(x2 -> x1L), or the environment along 'dir', unweighted
  float environmentPdf = 0.0f;  // ... the environment's NEE density along 'dir' (MIS), if so
  glm::vec3 beyond{0.0f};  // radiance leaving x2 towards x1L without Le(x2), per unit throughput
  PathSampler sampler;     // the left path's numbers: the right sample's NEE draws them too
  VertexNumbers numbers;   // ... those its first vertex drew, which a reused sample draws again
  // The left path's light sample at x1L if it is a light at infinity, which the right
  // sample's NEE, drawing the same numbers, would sample again to the bit, or a punctual
  // light, which it samples again from x1R (leftShadowEdge compares its point); else invalid.
  LightSample light;
  // Whether the left path's NEE at x1L traced a shadow ray, and what it found: the right
  // sample, drawing the same numbers, aims at the same light point, and this answer stands
  // for its own (the approximations, at the top of this file).
  bool shadowTraced = false;
  bool shadowBlocked = false;
};

// One eye's image as seen from the other: where a point lands in it (the linear ray map
// inverted) and how many samples per pixel it records.
struct EyeWindow {
  EyeCamera camera;
  uint32_t stride = 0;       // slots per pixel: samples [0, stride) of a pixel are recorded
  float pixelAngle = 0.0f;   // angle subtended by one pixel at the image centre (radians)
  glm::mat3 toWindow{1.0f};  // inverse of [rayDx rayDy rayBase]: world offset -> (px, py, 1) * t

  // For a frame of 'camera' with up to 'samplesPerPixel' samples.
  void set(const EyeCamera& camera, uint32_t samplesPerPixel);
};

// Record slots left uninitialised until a left path writes one (startPath), which its stamp
// then vouches for (StereoPaths::stamps): a 960x1080 frame's 220 MB are first touched by
// the tiles that record into them, in parallel, and never where a pixel records nothing
// (the sky), instead of all by one thread before the frame (a median 0.14 s, once 0.85 s,
// of `photovr render`'s first frame here; docs/MEASUREMENTS.md, "Serial passes left in the
// frame"). FirstBounce is an aggregate, so the storage's bytes hold its objects once
// written (C++20 implicit lifetime).
class RecordSlots {
 public:
  size_t size() const { return size_; }
  // n slots, none written (what the old slots held is gone).
  void resize(size_t n) {
    data_.reset(static_cast<FirstBounce*>(::operator new[](n * sizeof(FirstBounce))));
    size_ = n;
  }
  FirstBounce& operator[](size_t i) { return data_[i]; }
  const FirstBounce& operator[](size_t i) const { return data_[i]; }
  const FirstBounce* data() const { return data_.get(); }

 private:
  struct Release {
    void operator()(FirstBounce* p) const { ::operator delete[](p); }
  };
  std::unique_ptr<FirstBounce[], Release> data_;
  size_t size_ = 0;
};
static_assert(std::is_trivially_destructible_v<FirstBounce>);

// The first bounces of the eye traced first in a frame, for the other eye (in this file
// "left" is the eye that records, "right" the one that reuses; the eyes take turns,
// stereoTurnsOf). Its window is the recording eye's.
struct StereoPaths : EyeWindow {
  RecordSlots bounces;           // pixel * stride + sample; read only where stamped
  std::vector<uint32_t> stamps;  // per slot: the generation that wrote it
  uint32_t generation = 0;       // this frame's
  // On frames the right eye goes first: the left eye's window, whose pixels' numbers the
  // right eye's samples draw (ownPathCounters).
  EyeWindow leftEye;

  // Empties every slot for a frame of 'camera' with up to 'samplesPerPixel' samples.
  void reset(const EyeCamera& camera, uint32_t samplesPerPixel);
  // Slot of a pixel's sample for this frame's left path to record into, or null.
  FirstBounce* slot(size_t pixel, uint32_t sample) {
    if (sample >= stride) return nullptr;
    const size_t i = pixel * stride + sample;
    stamps[i] = generation;
    return &bounces[i];
  }
};

// Whether the left sample's bounce at x1L could have been 'w' (its pdf there is > 0): a
// reflection above x1L's shading and geometric horizons, from a view above the shading one
// (what sampleBsdf and the tracer's side test let through).
inline bool leftCovers(const FirstBounce& b, const glm::vec3& w) {
  return b.woAbove && glm::dot(w, b.normal) > 0.0f && glm::dot(w, b.geometricNormal) > 0.0f;
}

// The split of a right vertex's bounce directions between the reused left sample and its
// own (the derivation at the top): a direction w is the reused term's if the right vertex's
// own pdf there is at most kReusePdfRatio times g(w), the left pdf as the right vertex
// estimates it (its own material prepared in x1L's frame, for x1L's view, with x1L's lobe
// choice; 0 wherever leftCovers says the left pdf is 0), and the right sample's own
// otherwise. Both terms test the same g, so the two regions split the directions exactly,
// whatever g's error; g only decides how well the split keeps the reused term's weight
// f / pdf_L within kReusePdfRatio of the own sample's.
//
// Where the two vertices share both normals and the left view is above its horizon, the
// left support holds the right's, and where the left also picks each lobe at least
// 1 / kReusePdfRatio as often as the right, the left pdf is within that ratio of the right's
// but for the view change, which the roughness test below bounds (the usual case on a flat
// surface): there every direction is the reused term's ('whole'), and the right sample
// draws nothing of its own. (Any split with the reused part inside the left's support is
// unbiased; this choice only skips computing g where it would change next to nothing.)
constexpr float kReusePdfRatio = 2.0f;

// Whether every direction of the right vertex is the reused term's (below).
bool reusesWhole(const FirstBounce& b, const SurfaceHit& right, const BsdfVertex& rightVertex,
                 const glm::vec3& wo);

class ReuseSplit {
 public:
  // 'wo': the right view (unit, towards the right eye).
  ReuseSplit(const FirstBounce& b, const SurfaceHit& right, const BsdfVertex& rightVertex,
             const glm::vec3& wo);
  // Every direction of the right vertex is the reused term's.
  bool whole() const { return whole_; }
  // Whether w, whose pdf at the right vertex is rightPdf, belongs to the reused term.
  bool reused(const glm::vec3& w, float rightPdf) const {
    return whole_ || rightPdf <= kReusePdfRatio * leftPdf(w);
  }

 private:
  float leftPdf(const glm::vec3& w) const;
  const FirstBounce& b_;
  bool whole_ = false;
  Frame frame_;
  BsdfVertex vertex_;
};

// What a reused right sample's first vertex needs of the split: whether the left's bounce
// direction is the reused term's (reuseBounce adds it then), and whether the right sample's
// own direction, drawn with the left's numbers, lies outside it (it traces its own bounce).
struct SplitAnswers {
  bool leftDirReused = false;
  bool ownTraced = false;
};

// Primary hits whose shading normals are closer than acos(kPartnerNormalCos) ~ 25 degrees,
// and whose positions are within kPartnerPixels footprints of a left pixel, are the same
// surface point for the shift (the footprint of the nearest left pixel is up to ~0.7 pixel
// away; 1.5 leaves room for its jitter).
constexpr float kPartnerNormalCos = 0.9f;
constexpr float kPartnerPixels = 1.5f;
// 'whole' also needs the right vertex's lobes wide against the views' change, which it
// leaves to the reused term: its GGX alpha at least the angle between the eyes' views of
// it (then the right lobe's peak, which the view change moves by about half that angle in
// half-vector space, sits where the left lobe's D is still >= 0.64 of its peak:
// 1 / (1 + 1/4)^2, so f / pdf grows by <= 1.6x), and never below mirror-like roughness
// (kMirrorRoughness, 0.1: alpha 0.01 is a near-delta lobe whatever the angle). A smoother
// vertex (a glossy lobe, a mirror, a smooth coat on a diffuse base) is split like a tilted
// one: its thin lobe where the left's does not cover it is its own to trace, and its
// diffuse base is reused (spheres: 99 % of the right eye's samples reused against 94 % when
// smooth vertices traced all their paths themselves; 96 % since mirror-like ones, below,
// have no partner).
constexpr float kReuseMinRoughness = 0.1f;

// A right vertex whose reflection is mostly a mirror-like lobe (roughness under
// kReuseMinRoughness, its specular F0 at least its diffuse albedo in luminance: a smooth
// metal) has no partner, as glass has none: its own path, drawing the left pixel's numbers.
// Between the eyes' views (0.3-1 degree in a room) such a lobe sits a few alphas from the
// left's, so the split reuses only its tails and traces its peak anyway, and the split's
// boundary adds noise its own path does not have: a mirror's reused standard error was 5-6x
// its own paths' (StereoReuse.AMirrorLikeVertex...), spheres' mirror's per-pixel variance
// over 16 Sobol frames 12-18x. A smooth dielectric's diffuse base carries its noise and
// keeps its partner (1.0x the own standard error).
bool mirrorLike(const BsdfParams& bsdf);

// How one eye's tracer takes part: the eye traced first records into 'record' (which it
// resets), the other reuses 'reuse'; both null: stereo reuse off. 'leftEye': the right eye's
// window into the left eye's image, whose pixels' numbers its samples draw (the left's
// records when it reuses them); null for the left eye.
struct CausticPaths;  // trace/caustics.h

struct StereoRole {
  StereoPaths* record = nullptr;
  const StereoPaths* reuse = nullptr;
  const EyeWindow* leftEye = nullptr;
  // The frame's light-traced caustic paths, traced by the eye that goes first and connected
  // to each eye (trace/caustics.h); null: each eye traces its own. Set with reuse on or off.
  CausticPaths* caustics = nullptr;
  // Whether its samples look into the other eye's image (for a partner, or their numbers).
  bool looksAcross() const { return reuse || leftEye; }
};

// The eyes of a frame in the order they are traced, and each eye's role.
struct StereoTurns {
  std::array<int, 2> order{0, 1};
  std::array<StereoRole, 2> roles{};  // by eye
};

// Frame 'frame' of 'eyeCount' eyes (left 'leftCamera') with stereo reuse 'on': the eyes take
// turns to go first, the left on even frames, so that neither eye always carries what
// reuse adds to the variance. Whichever eye goes first, the samples of a left pixel and of the
// right pixels it stands for draw that left pixel's numbers (ownPathCounters), so each pair
// follows one Sobol sequence over the frames. Off, or one eye: left then right, no roles.
StereoTurns stereoTurnsOf(bool on, int eyeCount, uint32_t frame, StereoPaths& paths,
                          const EyeCamera& leftCamera, uint32_t samplesPerPixel);

// A right-eye sample looking for a partner: seen from 'eye' (the right eye's position)
// through its pixel's centre + 'offset' (the sample's sub-pixel position, the same in both
// eyes); 'centreRay' is a ray (of any length) through that pixel's centre; 'sample' is its index
// among the pixel's samples (the left slot it may reuse).
struct RightSample {
  glm::vec3 eye{0.0f}, centreRay{0.0f, 0.0f, -1.0f};
  glm::vec2 offset{0.0f};
  uint32_t sample = 0;
};

constexpr uint32_t kNoLeftPixel = ~0u;

// The left sample the right eye's sample at 'hit' reuses, or null: its own path. Either
// way '*leftPixel' (if given) is the left pixel that stands for the right pixel (where its
// centre on x1R's surface projects), or kNoLeftPixel where there is none.
const FirstBounce* findPartner(const StereoPaths& left, const SurfaceHit& hit,
                               const RightSample& right, uint32_t* leftPixel = nullptr);

// findPartner's left pixel alone, in a window with no records (the right eye goes first).
uint32_t leftPixelOf(const EyeWindow& left, const SurfaceHit& hit, const RightSample& right);

// findPartner in two steps, for a caller that looks up many pixels' partners (the hybrid's
// tiles): the left pixel that stands for a right sample at 'hit' and the left footprint
// there, squared (the same for every sample of a right pixel but for RightSample::sample,
// which the first step ignores), then the partner in that pixel's records. In between, the
// caller can ask for the records ahead of reading them (prefetchPartner): the record's
// first read was a fifth of findPartner's time, a miss at every pixel (perf annotate).
// findPartner(left, hit, right, &leftPixel) is partnerIn(left, standingPixelOf(left, hit,
// right), right.sample, hit, &leftPixel).
struct StandingPixel {
  uint32_t pixel = kNoLeftPixel;  // y * width + x in the left window; kNoLeftPixel: none
  float footprint2 = 0.0f;
};
StandingPixel standingPixelOf(const EyeWindow& left, const SurfaceHit& hit,
                              const RightSample& right);
void prefetchPartner(const StereoPaths& left, const StandingPixel& standing);
// A tile's samples ask for their partner records this many standing pixels ahead of the one
// they read: asked for all at once, a tile's 256 records (~1,100 cache lines) were a burst
// the memory system queued, and spheres' second eye at 960 x 1080 took 2.5 % longer (82.1
// against 80.1 ms, 4 alternating runs of photovr_bench_stereo; 8 ahead read the same; at
// 120 x 135, whose records stay in cache, the same; docs/MEASUREMENTS.md).
constexpr size_t kPartnerPrefetchAhead = 16;
// Called as a tile reaches standing[i], in order from 0: asks for the records of
// standing[i + kPartnerPrefetchAhead], and at i = 0 for those of every one before it too.
// Inline: called for every pixel of a reusing eye.
inline void prefetchPartnersAhead(const StereoPaths& left, std::span<const StandingPixel> standing,
                                  size_t i) {
  const size_t first = i == 0 ? 0 : i + kPartnerPrefetchAhead;
  const size_t last = std::min(i + kPartnerPrefetchAhead + 1, standing.size());
  for (size_t k = first; k < last; ++k) prefetchPartner(left, standing[k]);
}
const FirstBounce* partnerIn(const StereoPaths& left, const StandingPixel& standing,
                             uint32_t sample, const SurfaceHit& hit, uint32_t* leftPixel = nullptr);

// Whether the left sample 'b' (a record of 'left' this frame) is at the edge of a shadow
// its NEE ray found: it aimed at a punctual light (the sun, a lamp), and a horizontal
// neighbour's sample of the same index aimed at that light too and got the other answer. A
// right sample reusing 'b' then traces its own shadow ray instead of taking b's answer
// (leftShadowAnswers in trace/path_tracer.cpp): the edge would otherwise sit where the
// left's samples put it, moved by up to the partner's distance, a bias no number of frames
// removes (spheres' floor: 5-6 % of its trimmed relMSE at 32 frames, docs/MEASUREMENTS.md).
// A punctual light's shadow edge (one for every sample that aims at it) between x1L and x1R,
// which are within kPartnerPixels footprints and mostly apart along the row (the eyes'
// disparity), lies between b and a row neighbour unless it runs along the row. Neighbours
// that sampled another light, or the environment or an area light (whose points differ
// from sample to sample, so their answers differ by chance), do not count: there the left's
// answer stands, as before. So the edge is found only where a neighbour picked the same
// light: with one sun and a sky, most of the time; among atrium's four lamps, a quarter of
// the lamps' bias went (bench_stereo's shadow answers; docs/MEASUREMENTS.md).
bool leftShadowEdge(const StereoPaths& left, const FirstBounce& b);

// The numbers a right sample without a partner draws for its own path: the left eye's at
// 'leftPixel' (findPartner's), whose sample a right sample of the same pixel reuses in
// other frames, so that the right pixel keeps one Sobol sequence over the frames (at an
// occlusion edge the jitter moves its samples between a partner and none, and mixing its
// own sequence with the left pixel's lost the stratification of both: atrium's right eye
// had 9.4-10.3 % more variance per sample than its own paths, 8.1-8.5 % with this, and
// 4.1-4.6 % once findPartner stopped falling back to a neighbour's sample); its own where
// no left pixel stands for it. The left eye is eye 0, and its samples draw their own pixel's.
inline SampleCounters ownPathCounters(SampleCounters own, uint32_t leftPixel) {
  if (leftPixel == kNoLeftPixel) return own;
  own.pixel = leftPixel;
  own.eye = 0;
  return own;
}

// The window a role's samples look into: the records it reuses, or the left eye's.
inline const EyeWindow& windowOf(const StereoRole& role) {
  return role.reuse ? *role.reuse : *role.leftEye;
}

// A sample's partner in the other eye's records (findPartner), or null with 'counters', the
// numbers its own path draws: a right sample's turned to its left pixel's (ownPathCounters),
// whether the right eye reuses or goes first; a left sample's its own. 'standing': the
// sample's standing pixel in windowOf(role) (standingPixelOf), for samples that look across.
inline const FirstBounce* partnerOrOwnNumbers(const StereoRole& role, const SurfaceHit& hit,
                                              const StandingPixel& standing, uint32_t sample,
                                              SampleCounters& counters) {
  const bool right = role.leftEye != nullptr;
  uint32_t leftPixel = kNoLeftPixel;
  const FirstBounce* partner = nullptr;
  if (role.reuse)
    partner = partnerIn(*role.reuse, standing, sample, hit, right ? &leftPixel : nullptr);
  else if (right && sample < role.leftEye->stride)
    leftPixel = standing.pixel;
  if (!partner && right) counters = ownPathCounters(counters, leftPixel);
  return partner;
}

// The same from the sample itself (pt, whose every sample has a hit of its own).
inline const FirstBounce* partnerOrOwnNumbers(const StereoRole& role, const SurfaceHit& hit,
                                              const RightSample& sample, SampleCounters& counters) {
  return partnerOrOwnNumbers(role, hit, standingPixelOf(windowOf(role), hit, sample), sample.sample,
                             counters);
}

}  // namespace photovr
