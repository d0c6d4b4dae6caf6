// Owen-scrambled Sobol points, compiled by both the kernels and the host (as counter_random.h, so that host
// references draw the very points a kernel drew). A record's guided rays take them (kernels/records.cl guided_ray), and
// so does a radiance-cached pixel's guide share (kernels/glossy.cl guide_share):
// independent random numbers leave a few dozen rays a plain Monte Carlo estimate, whose variance falls as 1 / n, while
// a scrambled net spreads them over the cones it picks and over each cone's directions, and each point stays uniform
// on its own, so the estimate stays unbiased (Owen 1997, "Scrambled net variance for integrals of smooth functions").
#ifndef RCSPLAT_LOW_DISCREPANCY_H
#define RCSPLAT_LOW_DISCREPANCY_H
#include "counter_random.h"

// Dimension d (0, 1 or 2) of Sobol point `index`, as 32 bits of binary fraction, unscrambled. A dimension's direction
// numbers v_i = m_i / 2^i come from its primitive polynomial's recurrence (Bratley and Fox 1988): dimension 0 is
// van der Corput's (every m_i = 1), dimension 1 takes x + 1 (m_i = 2 m_{i-1} ^ m_{i-1}, m_1 = 1), dimension 2
// x^2 + x + 1 (m_i = 2 m_{i-1} ^ 4 m_{i-2} ^ m_{i-2}, m_1 = 1, m_2 = 3; Joe and Kuo's initial numbers).
inline rc_uint sobol_bits(rc_uint index, rc_uint d) {
  rc_uint x = 0u, m_prev = 1u, m_prev2 = 0u;
  for (rc_uint i = 1u; index != 0u && i <= 32u; ++i, index >>= 1) {
    rc_uint m = 1u;
    if (d == 1u) m = i == 1u ? 1u : (m_prev << 1) ^ m_prev;
    if (d == 2u) m = i == 1u ? 1u : i == 2u ? 3u : (m_prev << 1) ^ (m_prev2 << 2) ^ m_prev2;
    if (index & 1u) x ^= m << (32u - i);
    m_prev2 = m_prev;
    m_prev = m;
  }
  return x;
}

// Owen's nested uniform scramble, to the depth that the first 2^OWEN_DEPTH points of a net use: each of the top bits
// flips or not by a coin that the bits above it (unscrambled) and `seed` toss, so points that share a prefix move
// together and a net stays a net. Below that depth those points' bits are all zero, so their scramble there is a
// uniform fill chosen by the whole prefix: the same as scrambling every bit, at under half the hashes (all 24 bits one
// by one cost the Cornell box's records 11% of their time). A coin hashes its node before mixing in the seed: coins of
// hash_u32(seed ^ node) passed the tests of tests/low_discrepancy_test.cpp but failed both glossy hard cases of
// tests/hard_cases_test.cpp (block error 8x and 6x), for a reason not found.
#define OWEN_DEPTH 10u
inline rc_uint owen_scramble(rc_uint x, rc_uint seed) {
  rc_uint out = x;
  for (rc_uint b = 0u; b < OWEN_DEPTH; ++b) {
    rc_uint node = (1u << b) | (b == 0u ? 0u : x >> (32u - b));  // the b bits above bit 31 - b, behind a marker bit
    out ^= (hash_u32(seed ^ hash_u32(node ^ 0x5bd1e995u)) >> 31) << (31u - b);
  }
  return out ^ (hash_u32(seed ^ hash_u32(x >> (32u - OWEN_DEPTH))) >> OWEN_DEPTH);
}

// Dimension d of point `index` of the net scrambled by `seed`, in [0, 1): the same number on every device and the
// host.
inline float scrambled_sobol01(rc_uint index, rc_uint d, rc_uint seed) {
  rc_uint x = owen_scramble(sobol_bits(index, d), hash_u32(seed ^ (0x68bc21ebu * (d + 1u))));
  return (float)(x >> 8) * (1.0f / 16777216.0f);
}

// The three coordinates of point `index` of the net scrambled by `seed`: a guided ray's cone (*u) and its direction in
// the cone (*v, *w).
inline void scrambled_sobol3(rc_uint index, rc_uint seed, float* u, float* v, float* w) {
  *u = scrambled_sobol01(index, 0u, seed);
  *v = scrambled_sobol01(index, 1u, seed);
  *w = scrambled_sobol01(index, 2u, seed);
}

#endif
