#include "common/random.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace robodds {
namespace {

TEST(StableHash, IsFnv1a) {
  EXPECT_EQ(stable_hash(""), 14695981039346656037ULL);
  EXPECT_EQ(stable_hash("a"), 0xaf63dc4c8601ec8cULL);
}

TEST(DeriveSeed, DependsOnSeedAndName) {
  EXPECT_EQ(derive_seed(1, "x"), derive_seed(1, "x"));
  EXPECT_NE(derive_seed(1, "x"), derive_seed(2, "x"));
  EXPECT_NE(derive_seed(1, "x"), derive_seed(1, "y"));
}

TEST(StandardNormal, HasUnitMomentsAndIsReproducible) {
  RandomEngine a(derive_seed(7, "moments"));
  RandomEngine b(derive_seed(7, "moments"));
  const int n = 200000;
  double sum = 0.0;
  double sum_sq = 0.0;
  for (int i = 0; i < n; ++i) {
    const double x = standard_normal(a);
    ASSERT_EQ(x, standard_normal(b));
    sum += x;
    sum_sq += x * x;
  }
  const double mean = sum / n;
  const double var = sum_sq / n - mean * mean;
  EXPECT_NEAR(mean, 0.0, 5.0 / std::sqrt(n));
  EXPECT_NEAR(var, 1.0, 0.02);
}

TEST(Uniform01, StaysInHalfOpenUnitInterval) {
  RandomEngine engine(3);
  for (int i = 0; i < 10000; ++i) {
    const double u = uniform01(engine);
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
  }
}

}  // namespace
}  // namespace robodds
