// Bit-for-bit comparison of two surface hits, for tests of paths that must build the same
// SurfaceHit another way (a batch, a table of constant material inputs).
#pragma once

#include <gtest/gtest.h>

#include "trace/surface.h"

namespace photovr::testing {

inline void expectSameBits(const SurfaceHit& a, const SurfaceHit& b) {
  EXPECT_EQ(a.position, b.position);
  EXPECT_EQ(a.positionError, b.positionError);
  EXPECT_EQ(a.geometricNormal, b.geometricNormal);
  EXPECT_EQ(a.shadingNormal, b.shadingNormal);
  EXPECT_EQ(a.emission, b.emission);
  EXPECT_EQ(a.frontFace, b.frontFace);
  EXPECT_EQ(a.instance, b.instance);
  EXPECT_EQ(a.triangle, b.triangle);
  const BsdfParams &p = a.bsdf, &q = b.bsdf;
  EXPECT_EQ(p.baseColor, q.baseColor);
  EXPECT_EQ(p.metallic, q.metallic);
  EXPECT_EQ(p.roughness, q.roughness);
  EXPECT_EQ(p.dielectricF0, q.dielectricF0);
  EXPECT_EQ(p.dielectricF90, q.dielectricF90);
  EXPECT_EQ(p.transmission, q.transmission);
  EXPECT_EQ(p.eta, q.eta);
  EXPECT_EQ(p.thinWalled, q.thinWalled);
  EXPECT_EQ(p.sheenColor, q.sheenColor);
  EXPECT_EQ(p.sheenRoughness, q.sheenRoughness);
  EXPECT_EQ(p.clearcoat, q.clearcoat);
  EXPECT_EQ(p.clearcoatRoughness, q.clearcoatRoughness);
  EXPECT_EQ(p.coatNormal, q.coatNormal);
}

}  // namespace photovr::testing
