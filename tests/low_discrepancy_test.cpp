// The scrambled Sobol points of a record's guided rays (kernels/low_discrepancy.h): the right sequence, nets that
// survive the scramble, and points that each stay uniform (what keeps the guided estimate unbiased). The kernels
// compile the same header; tests/records_test.cpp checks that a record's guided rays on the device are the host's.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <vector>

#include "kernels/low_discrepancy.h"

namespace {

// Sobol's sequence built another way: in Gray-code order (Antonov and Saleev 1979: point n + 1 is point n with one
// direction number xor-ed in), from direction numbers in Bratley and Fox's v form, v_i = a_1 v_{i-1} ^ ... ^
// v_{i-s} ^ (v_{i-s} >> s). Gray-code point n is natural-order point n ^ (n >> 1).
std::vector<uint32_t> gray_code_sobol(unsigned d, unsigned count) {
  std::array<uint32_t, 33> v{};
  for (unsigned i = 1; i <= 32; ++i) {
    if (d == 0) v[i] = 1u << (32 - i);
    else if (d == 1) v[i] = i == 1 ? 1u << 31 : v[i - 1] ^ (v[i - 1] >> 1);  // x + 1
    else v[i] = i == 1 ? 1u << 31 : i == 2 ? 3u << 30 : v[i - 1] ^ v[i - 2] ^ (v[i - 2] >> 2);  // x^2 + x + 1
  }
  std::vector<uint32_t> points(count);
  uint32_t x = 0;
  for (unsigned n = 0; n < count; ++n) {
    points[n] = x;
    unsigned c = 1;  // the lowest zero bit of n, counted from 1
    for (unsigned m = n; m & 1u; m >>= 1) ++c;
    x ^= v[c];
  }
  return points;
}

// Pearson's chi-square of counts against the same expected count in every bin.
double chi_square(const std::vector<double>& counts) {
  double total = 0.0, chi2 = 0.0;
  for (double c : counts) total += c;
  const double expected = total / double(counts.size());
  for (double c : counts) chi2 += (c - expected) * (c - expected) / expected;
  return chi2;
}

// Whether the first 2^m points of the net (scrambled by `seed`, or not scrambled) put exactly 2^t points in every
// elementary box of volume 2^(t - m) over the dimensions `dims`: a (t, m, s)-net.
bool is_net(const std::vector<unsigned>& dims, unsigned m, unsigned t, uint32_t seed, bool scrambled) {
  const unsigned count = 1u << m, s = unsigned(dims.size());
  std::vector<unsigned> splits(s, 0);
  // Every way of splitting m - t bits of resolution among the dimensions.
  while (true) {
    unsigned used = 0;
    for (unsigned k : splits) used += k;
    if (used == m - t) {
      std::map<std::vector<unsigned>, unsigned> boxes;
      for (unsigned i = 0; i < count; ++i) {
        std::vector<unsigned> box(s);
        for (unsigned j = 0; j < s; ++j) {
          double x = scrambled ? double(scrambled_sobol01(i, dims[j], seed))
                               : double(sobol_bits(i, dims[j])) / 4294967296.0;
          box[j] = unsigned(std::floor(x * double(1u << splits[j])));
        }
        ++boxes[box];
      }
      if (boxes.size() != (1u << (m - t))) return false;
      for (const auto& [box, n] : boxes)
        if (n != (1u << t)) return false;
    }
    unsigned j = 0;
    while (j < s && ++splits[j] > m - t) splits[j++] = 0;
    if (j == s) return true;
  }
}

}  // namespace

TEST(LowDiscrepancy, SobolIsTheGrayCodeConstructionInNaturalOrder) {
  for (unsigned d = 0; d < 3; ++d) {
    const std::vector<uint32_t> gray = gray_code_sobol(d, 4096);
    for (uint32_t n = 0; n < 4096; ++n)
      ASSERT_EQ(sobol_bits(n ^ (n >> 1), d), gray[n]) << "dimension " << d << " point " << n;
  }
}

// Dimensions 0 and 1 are a (0, 2)-sequence, and all three a (1, 3)-sequence: every 2^m points leave no elementary box
// of the right volume empty or doubly filled. Owen's scramble keeps that, for every seed.
TEST(LowDiscrepancy, ScrambledPointsStayNets) {
  for (unsigned m : {4u, 6u, 8u}) {
    EXPECT_TRUE(is_net({0, 1}, m, 0, 0, false)) << m;
    EXPECT_TRUE(is_net({0, 1, 2}, m, 1, 0, false)) << m;
    for (uint32_t seed : {1u, 77u, 0xdeadbeefu}) {
      EXPECT_TRUE(is_net({0, 1}, m, 0, seed, true)) << m << " seed " << seed;
      EXPECT_TRUE(is_net({1, 2}, m, 1, seed, true)) << m << " seed " << seed;
      EXPECT_TRUE(is_net({0, 1, 2}, m, 1, seed, true)) << m << " seed " << seed;
    }
  }
}

// Over many seeds each point of the net, in each dimension, is uniform on [0, 1): a chi-square test over 32 bins
// (31 degrees of freedom; 70 is beyond its 99.99th percentile), and the mean within 4 standard errors of 1/2.
TEST(LowDiscrepancy, EachScrambledPointIsUniform) {
  const unsigned seeds = 32768, bins = 32;
  for (uint32_t point : {0u, 1u, 5u, 63u}) {
    for (unsigned d = 0; d < 3; ++d) {
      std::vector<double> count(bins, 0.0);
      double sum = 0.0;
      for (uint32_t seed = 0; seed < seeds; ++seed) {
        float x = scrambled_sobol01(point, d, hash_u32(seed));
        ASSERT_GE(x, 0.0f);
        ASSERT_LT(x, 1.0f);
        count[unsigned(x * float(bins))] += 1.0;
        sum += x;
      }
      EXPECT_LT(chi_square(count), 70.0) << "point " << point << " dimension " << d;
      EXPECT_NEAR(sum / seeds, 0.5, 4.0 * std::sqrt(1.0 / 12.0 / seeds)) << "point " << point << " dimension " << d;
    }
  }
}

// Owen's scramble tosses an independent coin at every node: two points that part at the first bit then move
// independently below it. Over many seeds, points 0 and 1 of each dimension (one in each half) have their positions
// within their halves independent: a chi-square test of their 8 x 8 joint histogram (63 degrees of freedom; 130 is
// beyond its 99.99th percentile).
TEST(LowDiscrepancy, PointsInDifferentHalvesMoveIndependently) {
  const unsigned seeds = 65536, bins = 8;
  for (unsigned d = 0; d < 3; ++d) {
    std::vector<double> joint(bins * bins, 0.0);
    for (uint32_t seed = 0; seed < seeds; ++seed) {
      double a = 2.0 * double(scrambled_sobol01(0, d, hash_u32(seed)));
      double b = 2.0 * double(scrambled_sobol01(1, d, hash_u32(seed)));
      a -= std::floor(a);
      b -= std::floor(b);
      joint[unsigned(a * bins) * bins + unsigned(b * bins)] += 1.0;
    }
    EXPECT_LT(chi_square(joint), 130.0) << "dimension " << d;
  }
}
