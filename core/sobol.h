// Owen-scrambled Sobol points with hash-based scrambling (Burley, "Practical Hash-based
// Owen Scrambling", JCGT 9(4), 2020): every point a pure function of (index, seed), so a
// renderer draws them counter-based, in any order, on any thread.
//
// Only Sobol's first two dimensions are used, the (0, 2)-sequence in base 2 (every aligned
// block of 2^m consecutive points is a (0, m, 2)-net: one point in every elementary interval
// of area 2^-m). Higher dimensions are padded: each 1D or 2D number a path draws comes from
// its own copy of the sequence, whose index is Owen-scrambled with a seed of its own
// (Burley 2020, sec. 4, "shuffled" Sobol), so that different numbers of one path are not
// correlated while each stays stratified over the sample index. (pbrt-v4's
// PaddedSobolSampler pads the same way but shuffles with a random permutation of the
// pixel's sample count; an Owen-scrambled index needs no count, so it runs on over the
// frames.) Sobol's higher dimensions are not used: their 2D projections are far from
// (0, 2) (dimensions 2 and 3 of Joe & Kuo's table make only a (2, m, 2)-net; with them as
// the first BSDF sample, forming a 4D net with the pixel position, bench_sampler measured
// no gain beyond its noise). The nested shuffle keeps some structure between draws: indices 2j
// and 2j + 1 land in opposite halves in every draw, so a pair of draws is not quite a
// uniform pairing of two stratified sequences (its quadrant counts vary 2x as much as a
// Latin hypercube's; tests/trace/sobol_test.cpp measures it), still far below random's.
#pragma once

#include <array>
#include <cstdint>

#include <glm/glm.hpp>

namespace photovr {

inline uint32_t reverseBits(uint32_t v) {
  v = __builtin_bswap32(v);
  v = ((v & 0x0f0f0f0fu) << 4) | ((v >> 4) & 0x0f0f0f0fu);
  v = ((v & 0x33333333u) << 2) | ((v >> 2) & 0x33333333u);
  return ((v & 0x55555555u) << 1) | ((v >> 1) & 0x55555555u);
}

// Nested uniform (Owen) scrambling of the binary fraction v * 2^-32: digit k is flipped by a
// pseudo-random function of digits 1..k-1 and the seed. In reversed bit order that is a
// permutation where every bit depends only on the bits below it, which additions and
// multiplications by constants give: the Laine-Karras construction (Laine & Karras,
// "Stratified sampling for stochastic transparency", 2011) with the constants of Vegdahl's
// improved hash ("Building a better LK hash", 2021), as pbrt-v4's FastOwenScrambler. Being a
// nested permutation, it maps every elementary interval onto one of the same size: nets stay
// nets, and each scrambled point is uniform on [0, 1).
inline uint32_t owenScramble(uint32_t v, uint32_t seed) {
  v = reverseBits(v);
  v ^= v * 0x3d20adeau;
  v += seed;
  v *= (seed >> 16) | 1u;
  v ^= v * 0x05526c56u;
  v ^= v * 0x53a22864u;
  return reverseBits(v);
}

namespace sobol_detail {

// Generator matrix of Sobol's second dimension, column j = m_j << (32 - j) (Bratley & Fox,
// "Algorithm 659", 1988): primitive polynomial x + 1, m_1 = 1, m_j = m_{j-1} ^ (m_{j-1} << 1)
// (Pascal's triangle mod 2). Written out as byte tables (column sets of 8 index bits), so a
// point costs four lookups instead of 32 conditional XORs.
constexpr std::array<uint32_t, 32> dimension1Columns() {
  std::array<uint32_t, 32> c{};
  uint32_t m = 1;
  for (int j = 1; j <= 32; ++j) {
    c[size_t(j - 1)] = m << (32 - j);
    m ^= m << 1;
  }
  return c;
}

constexpr std::array<std::array<uint32_t, 256>, 4> dimension1Tables() {
  const std::array<uint32_t, 32> columns = dimension1Columns();
  std::array<std::array<uint32_t, 256>, 4> t{};
  for (size_t b = 0; b < 4; ++b)
    for (uint32_t byte = 0; byte < 256; ++byte) {
      uint32_t v = 0;
      for (size_t bit = 0; bit < 8; ++bit)
        if (byte & (1u << bit)) v ^= columns[8 * b + bit];
      t[b][byte] = v;
    }
  return t;
}

inline constexpr std::array<std::array<uint32_t, 256>, 4> kDimension1 = dimension1Tables();

}  // namespace sobol_detail

// Unscrambled Sobol point 'index' as 32-bit fractions: dimension 0 is the van der Corput
// sequence (the bit-reversed index), dimension 1 the matrix above times the index.
inline uint32_t sobolDimension0(uint32_t index) {
  return reverseBits(index);
}
inline uint32_t sobolDimension1(uint32_t index) {
  const auto& t = sobol_detail::kDimension1;
  return t[0][index & 0xffu] ^ t[1][(index >> 8) & 0xffu] ^ t[2][(index >> 16) & 0xffu] ^
         t[3][index >> 24];
}

// Seeds derived from one by an odd-constant multiply and xor-shift (cheap; the scrambles
// themselves hash them further): distinct seeds for the index shuffle and each dimension.
inline uint32_t nextSeed(uint32_t seed) {
  seed = (seed ^ (seed >> 16)) * 0x7feb352du;
  return (seed ^ (seed >> 15)) * 0x846ca68bu;
}

// The 1D and 2D padded draws of Burley 2020, listing 4, as 32-bit fractions: index shuffled
// with one seed (a nested permutation of the index: each aligned block of 2^m indices onto
// one such block, so the first 2^m samples of any draw stay a net), then each coordinate
// Owen-scrambled with its own.
inline uint32_t shuffledSobol1D(uint32_t index, uint32_t seed) {
  const uint32_t shuffled = owenScramble(index, seed);
  return owenScramble(sobolDimension0(shuffled), nextSeed(seed));
}
inline glm::uvec2 shuffledSobol2D(uint32_t index, uint32_t seed) {
  const uint32_t shuffled = owenScramble(index, seed);
  const uint32_t sx = nextSeed(seed), sy = nextSeed(sx);
  return {owenScramble(sobolDimension0(shuffled), sx), owenScramble(sobolDimension1(shuffled), sy)};
}

// The Owen-scrambled (unshuffled) 2D Sobol sequence: what the pixel positions use, whose
// sequence order matters too (every prefix of 2^m frames is a net).
inline glm::uvec2 scrambledSobol2D(uint32_t index, uint32_t seed) {
  const uint32_t sx = nextSeed(seed), sy = nextSeed(sx);
  return {owenScramble(sobolDimension0(index), sx), owenScramble(sobolDimension1(index), sy)};
}

}  // namespace photovr
