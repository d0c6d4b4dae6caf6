// rcsplat's LDR-FLIP against NVIDIA's own implementation: the expected numbers are flip-evaluator 1.7's (PyPI) on the
// same formula images, printed by benchmarks/flip_test_values.py. benchmarks/flip_check.py does the same on renders.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "image/flip.h"

namespace rcsplat {
namespace {

constexpr int kWidth = 48, kHeight = 32;

// Keep in step with benchmarks/flip_test_values.py: a smooth colour field, and beside it the same field with a band of
// high-frequency noise and a black square.
void formula_images(std::vector<float>& reference, std::vector<float>& test) {
  reference.assign(size_t(kWidth) * kHeight * 3, 0.0f);
  test = reference;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x)
      for (int c = 0; c < 3; ++c) {
        const double r = 0.5 + 0.4 * std::sin(0.3 * x + 0.2 * y + c);
        double t = r + (x >= 10 && x < 30 ? 0.1 * std::sin(1.7 * x * y + c) : 0.0);
        if (x >= 5 && x < 10 && y >= 5 && y < 10) t = 0.0;
        const size_t i = (size_t(y) * kWidth + size_t(x)) * 3 + size_t(c);
        reference[i] = float(r);
        test[i] = float(std::fmin(std::fmax(t, 0.0), 1.0));
      }
}

TEST(Flip, MatchesNvidiasFlipEvaluator) {
  std::vector<float> reference, test;
  formula_images(reference, test);
  const FlipResult flip = ldr_flip(reference, test, kWidth, kHeight);
  // flip-evaluator computes in single precision; 2e-5 is a few of its rounding steps.
  EXPECT_NEAR(flip.mean, 0.0758812, 2e-5);
  struct Pixel {
    int x, y;
    double expected;
  };
  for (const Pixel& p : {Pixel{0, 0, 0.0054851}, Pixel{7, 7, 0.6886384}, Pixel{12, 20, 0.1453524},
                         Pixel{20, 3, 0.0941366}, Pixel{40, 25, 0.0}, Pixel{47, 31, 0.0}})
    EXPECT_NEAR(flip.error[size_t(p.y) * kWidth + size_t(p.x)], p.expected, 1e-4) << "pixel " << p.x << ", " << p.y;
}

TEST(Flip, IdenticalImagesDoNotDifferAndOrderDoesNotMatterForColour) {
  std::vector<float> reference, test;
  formula_images(reference, test);
  const FlipResult same = ldr_flip(reference, reference, kWidth, kHeight);
  for (float e : same.error) ASSERT_EQ(e, 0.0f);
  // FLIP's colour and feature differences are symmetric: swapping the images changes nothing.
  const FlipResult forward = ldr_flip(reference, test, kWidth, kHeight), backward = ldr_flip(test, reference, kWidth, kHeight);
  EXPECT_NEAR(forward.mean, backward.mean, 1e-12);
  // Black against white is as far apart as FLIP's colour scale goes.
  const std::vector<float> black(size_t(kWidth) * kHeight * 3, 0.0f), white(black.size(), 1.0f);
  EXPECT_GT(ldr_flip(black, white, kWidth, kHeight).mean, 0.9);
}

}  // namespace
}  // namespace rcsplat
