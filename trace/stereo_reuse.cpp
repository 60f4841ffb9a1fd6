#include "trace/stereo_reuse.h"

#include <algorithm>
#include <cmath>

namespace photovr {

void EyeWindow::set(const EyeCamera& cam, uint32_t samplesPerPixel) {
  camera = cam;
  stride = samplesPerPixel;
  const glm::vec3 dx = cam.rayDx(), dy = cam.rayDy(), base = cam.rayBase();
  toWindow = glm::inverse(glm::mat3(dx, dy, base));
  const glm::vec3 centre = base + dx * (0.5f * cam.width) + dy * (0.5f * cam.height);
  pixelAngle = glm::length(dx) / glm::length(centre);
}

void StereoPaths::reset(const EyeCamera& cam, uint32_t samplesPerPixel) {
  set(cam, samplesPerPixel);
  // Resized, not cleared: a slot counts only if this frame's generation stamped it (at
  // 960 x 1080 the slots are ~220 MB, too much to clear per frame).
  const size_t n = size_t(cam.width) * cam.height * stride;
  if (bounces.size() != n) bounces.resize(n);
  stamps.resize(n, 0);
  if (++generation == 0) {  // after 2^32 frames: start over with every stamp stale
    std::fill(stamps.begin(), stamps.end(), 0);
    generation = 1;
  }
}

StereoTurns stereoTurnsOf(bool on, int eyeCount, uint32_t frame, StereoPaths& paths,
                          const EyeCamera& leftCamera, uint32_t samplesPerPixel) {
  StereoTurns t;
  if (!on || eyeCount != 2) return t;
  if (frame % 2 == 0) {
    t.roles = {StereoRole{&paths, nullptr, nullptr}, StereoRole{nullptr, &paths, &paths}};
    return t;
  }
  paths.leftEye.set(leftCamera, samplesPerPixel);
  t.order = {1, 0};
  t.roles = {StereoRole{nullptr, &paths, nullptr}, StereoRole{&paths, nullptr, &paths.leftEye}};
  return t;
}

namespace {

// Whether the left vertex picks each BRDF lobe at least 1 / kReusePdfRatio as often as the
// right one.
bool lobesAlike(float left, float right) {
  return right <= kReusePdfRatio * left && 1.0f - right <= kReusePdfRatio * (1.0f - left);
}

// Whether the right vertex's lobes are wide enough for the views' change alone to be left
// to the reused term (kReuseMinRoughness): the smallest GGX alpha of its lobes at least the
// angle between the views ('toLeft', 'toRight': unit), and never mirror-like.
bool wideAgainstViews(const BsdfParams& bsdf, const glm::vec3& toLeft, const glm::vec3& toRight) {
  // A clear coat is a glossy lobe of its own roughness.
  const float roughness =
      bsdf.clearcoat > 0.0f ? std::min(bsdf.roughness, bsdf.clearcoatRoughness) : bsdf.roughness;
  if (!(roughness >= kReuseMinRoughness)) return false;
  // alpha >= acos(c), with alpha <= 1 < pi: c >= cos(alpha). atLeastCosOf, not a call of
  // libm's cosf on every reused sample of a flat surface (a fifth of this test's time, perf).
  return atLeastCosOf(glm::dot(toLeft, toRight), roughnessToAlpha(roughness));
}

}  // namespace

bool mirrorLike(const BsdfParams& bsdf) {
  if (!(bsdf.roughness < kReuseMinRoughness)) return false;
  const glm::vec3 f0 = glm::mix(bsdf.dielectricF0, bsdf.baseColor, bsdf.metallic);
  return luminance(f0) >= luminance(diffuseAlbedo(bsdf));
}

bool reusesWhole(const FirstBounce& b, const SurfaceHit& right, const BsdfVertex& rightVertex,
                 const glm::vec3& wo) {
  return b.woAbove && b.normal == right.shadingNormal &&
         b.geometricNormal == right.geometricNormal &&
         lobesAlike(b.specularProbability, rightVertex.specularProbability) &&
         wideAgainstViews(right.bsdf, b.wo, wo);
}

ReuseSplit::ReuseSplit(const FirstBounce& b, const SurfaceHit& right, const BsdfVertex& rightVertex,
                       const glm::vec3& wo)
    : b_(b) {
  whole_ = reusesWhole(b, right, rightVertex, wo);
  if (whole_) return;
  frame_ = Frame::fromZ(b.normal);
  vertex_ = prepareBsdfPdf(right.bsdf, frame_.toLocal(b.wo), b.specularProbability);
}

float ReuseSplit::leftPdf(const glm::vec3& w) const {
  if (!leftCovers(b_, w)) return 0.0f;
  return pdfBsdf(vertex_, frame_.toLocal(w));
}

namespace {

// Left sample 'sample' of pixel 'pixel', inside the left image, if it was recorded this frame and
// is the same surface point as the right hit for the shift: same instance, normals within
// kPartnerNormalCos, within 'maxDistance2' (squared) of it.
const FirstBounce* partnerAt(const StereoPaths& left, uint32_t pixel, uint32_t sample,
                             const SurfaceHit& hit, float maxDistance2) {
  const size_t slot = size_t(pixel) * left.stride + sample;
  if (left.stamps[slot] != left.generation) return nullptr;  // no left path this frame
  const FirstBounce& b = left.bounces[slot];
  if (b.instance != hit.instance) return nullptr;  // another object
  if (glm::dot(b.normal, hit.shadingNormal) < kPartnerNormalCos) return nullptr;
  const glm::vec3 d = b.position - hit.position;
  return glm::dot(d, d) <= maxDistance2 ? &b : nullptr;
}

// How far from x1R (in its pixel footprints) the right pixel's centre on x1R's tangent plane
// may lie: a sample is at most ~0.7 pixel from its pixel's centre, which a plane seen at a
// slant stretches by 1 / cos: 8 footprints hold it down to ~5 degrees above the plane.
constexpr float kCentreReach = 8.0f;

// The left window position (pixels) whose pixel holds the partner: that of the right
// pixel's centre on x1R's surface, where the centre ray meets x1R's tangent plane. It stays
// in one left pixel from frame to frame while the jitter moves x1R across the right pixel,
// also where the disparity changes across it (a floor seen at a slant: x1R's own position
// less the sample's offset crossed into the next left pixel for some offsets, and the right
// pixel mixed two left pixels' stratified sequences, ~3 % more variance on atrium). Where
// that point is beyond kCentreReach (the centre ray grazes the plane), x1R's position less
// the offset: the left pixel whose sample, at its centre + the offset as this one's, is
// nearest x1R. False: behind the left eye.
bool leftWindowPoint(const EyeWindow& left, const SurfaceHit& hit, const RightSample& right,
                     float footprint2, glm::vec2& window) {
  const glm::vec3& n = hit.geometricNormal;
  const float t = glm::dot(hit.position - right.eye, n) / glm::dot(right.centreRay, n);
  const glm::vec3 centre = right.eye + t * right.centreRay;
  const glm::vec3 d = centre - hit.position;
  const bool onPlane = t > 0.0f && glm::dot(d, d) <= kCentreReach * kCentreReach * footprint2;
  // (px t, py t, t): the linear ray map inverted.
  const glm::vec3 w =
      left.toWindow * ((onPlane ? centre : hit.position) - left.camera.pose.position);
  if (!(w.z > 0.0f)) return false;  // behind the left eye (or NaN)
  window = glm::vec2(w.x, w.y) / w.z - (onPlane ? glm::vec2(0.0f) : right.offset);
  return true;
}

}  // namespace

// The left pixel that stands for the right sample at 'hit', and the left footprint there
// squared; none: glass, behind the left eye, outside its image.
StandingPixel standingPixelOf(const EyeWindow& left, const SurfaceHit& hit,
                              const RightSample& right) {
  StandingPixel s;
  // Glass: reuseBounce shifts reflections only, and what is seen through glass moves
  // between the eyes by its own parallax, not the glass surface's.
  if (hit.bsdf.transmission > 0.0f) return s;
  const glm::vec3 offset = hit.position - left.camera.pose.position;
  // The footprint squared: (pixel angle x distance)^2, no square root.
  const float footprint2 = left.pixelAngle * left.pixelAngle * glm::dot(offset, offset);
  glm::vec2 window;
  if (!leftWindowPoint(left, hit, right, footprint2, window)) return s;
  const float px = window.x, py = window.y;
  if (!(px >= 0.0f && py >= 0.0f && px < float(left.camera.width) &&
        py < float(left.camera.height)))
    return s;
  s.pixel = uint32_t(py) * uint32_t(left.camera.width) + uint32_t(px);
  s.footprint2 = footprint2;
  return s;
}

void prefetchPartner(const StereoPaths& left, const StandingPixel& standing) {
  if (standing.pixel == kNoLeftPixel || left.stride == 0) return;
  const size_t slot = size_t(standing.pixel) * left.stride;
  __builtin_prefetch(&left.stamps[slot]);
  // Every line of the first sample's record: the partner test reads its first, but a reused
  // sample reads the rest right after (its numbers and sampler in startPath, a miss there
  // that was a third of startPath's time, perf annotate).
  const char* record = reinterpret_cast<const char*>(&left.bounces[slot]);
  for (size_t offset = 0; offset < sizeof(FirstBounce); offset += 64)
    __builtin_prefetch(record + offset);
  __builtin_prefetch(record + sizeof(FirstBounce) - 1);
}

const FirstBounce* partnerIn(const StereoPaths& left, const StandingPixel& standing,
                             uint32_t sample, const SurfaceHit& hit, uint32_t* leftPixel) {
  if (leftPixel) *leftPixel = kNoLeftPixel;
  // A sample the left does not record has neither a partner nor the left's numbers.
  if (sample >= left.stride || standing.pixel == kNoLeftPixel) return nullptr;
  if (leftPixel) *leftPixel = standing.pixel;
  if (mirrorLike(hit.bsdf)) return nullptr;
  // Where that sample is another surface (an edge, a thin object), none: a neighbour's
  // sample of this surface would give the right pixel another pixel's sequence in those
  // frames, and its own path draws this left pixel's numbers instead (ownPathCounters).
  return partnerAt(left, standing.pixel, sample, hit,
                   kPartnerPixels * kPartnerPixels * standing.footprint2);
}

namespace {

// Whether two left samples' NEE aimed at one punctual light: the same direction for one at
// infinity (the same sample to the bit), the same point for one at a finite distance (each
// computed from its own x1 as x1 + direction x distance, equal to float rounding: a few
// epsilons of the distance and of |x1|, within 1e-5 of them, ~80 epsilons; two punctual
// lights at one point cast the same shadows). Two lights nearer than that count as one:
// their neighbours' answers then only send more right samples to trace their own rays.
bool sameDeltaLight(const FirstBounce& a, const FirstBounce& b) {
  const LightSample &la = a.light, &lb = b.light;
  if (!lb.isDelta || la.atInfinity() != lb.atInfinity()) return false;
  if (la.atInfinity()) return la.direction == lb.direction;
  const glm::vec3 d =
      (a.position + la.direction * la.distance) - (b.position + lb.direction * lb.distance);
  const float tolerance = 1e-5f * (la.distance + glm::length(a.position));
  return glm::dot(d, d) <= tolerance * tolerance;
}

}  // namespace

bool leftShadowEdge(const StereoPaths& left, const FirstBounce& b) {
  if (!b.shadowTraced || !b.light.isDelta) return false;
  const size_t slot = size_t(&b - left.bounces.data());
  const size_t stride = left.stride, width = size_t(left.camera.width);
  const size_t x = (slot / stride) % width;
  for (const size_t neighbour :
       {x > 0 ? slot - stride : slot, x + 1 < width ? slot + stride : slot}) {
    if (neighbour == slot || left.stamps[neighbour] != left.generation) continue;
    const FirstBounce& n = left.bounces[neighbour];
    if (n.shadowTraced && n.shadowBlocked != b.shadowBlocked && sameDeltaLight(b, n)) return true;
  }
  return false;
}

const FirstBounce* findPartner(const StereoPaths& left, const SurfaceHit& hit,
                               const RightSample& right, uint32_t* leftPixel) {
  return partnerIn(left, standingPixelOf(left, hit, right), right.sample, hit, leftPixel);
}

uint32_t leftPixelOf(const EyeWindow& left, const SurfaceHit& hit, const RightSample& right) {
  if (right.sample >= left.stride) return kNoLeftPixel;
  return standingPixelOf(left, hit, right).pixel;
}

}  // namespace photovr
