// The DK2 lens for one panel pixel (dk2.md §6): hmd/lens.cpp screenToTan (LibOVR
// CatmullRom10 with chromatic terms) and lensSees, ported to float. Shared by the
// distortion pass (distort.comp) and the timewarp's per-panel-pixel table
// (timewarp_lut.comp), so both show the same lens. Needs compositor_shared.h first.

float lensKnot(DistortUniforms l, int i) {
  return i < 4 ? l.k0[i] : (i < 8 ? l.k1[i - 4] : l.k2[i - 8]);
}

float lensHermite(float p0, float m0, float p1, float m1, float t) {
  float v = 1.0 - t;
  return (p0 * (1.0 + 2.0 * t) + m0 * t) * v * v + (p1 * (1.0 + 2.0 * v) - m1 * v) * t * t;
}

float lensCatmullRom10(DistortUniforms l, float x) {
  x = max(x, 0.0);
  if (x >= 10.0) return lensKnot(l, 10) + (x - 10.0) * (lensKnot(l, 10) - lensKnot(l, 9));
  int s = min(int(x), 9);
  float t = x - float(s);
  if (s == 0)
    return lensHermite(1.0, lensKnot(l, 1) - lensKnot(l, 0), lensKnot(l, 1),
                       0.5 * (lensKnot(l, 2) - lensKnot(l, 0)), t);
  if (s == 9)
    return lensHermite(lensKnot(l, 9), 0.5 * (lensKnot(l, 10) - lensKnot(l, 8)), lensKnot(l, 10),
                       lensKnot(l, 10) - lensKnot(l, 9), t);
  return lensHermite(lensKnot(l, s), 0.5 * (lensKnot(l, s + 1) - lensKnot(l, s - 1)),
                     lensKnot(l, s + 1), 0.5 * (lensKnot(l, s + 2) - lensKnot(l, s)), t);
}

// What pixel p of this eye's half of the panel shows: the green channel's tan-angle,
// red and blue as multiples of it, and whether the lens sees the pixel at all.
struct LensRay {
  vec2 tanG;
  float scaleR, scaleB;
  bool sees;
};

LensRay lensRay(DistortUniforms l, ivec2 p) {
  vec2 screen = (vec2(p) + 0.5) * 2.0 / vec2(l.panel.xy) - 1.0;
  vec2 d = (screen - l.lens.xy) * l.lens.zw;
  float rsq = dot(d, d), maxR = l.k2.w;
  LensRay ray;
  ray.sees = all(lessThanEqual(abs(screen), vec2(1.0))) && rsq <= maxR * maxR;
  ray.tanG = d * lensCatmullRom10(l, 10.0 * rsq / (maxR * maxR));
  ray.scaleR = 1.0 + l.chroma.x + rsq * l.chroma.y;
  ray.scaleB = 1.0 + l.chroma.z + rsq * l.chroma.w;
  return ray;
}
