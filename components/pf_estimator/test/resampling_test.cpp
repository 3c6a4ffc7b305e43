#include "components/pf_estimator/resampling.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <vector>

namespace robodds::pf_estimator {
namespace {

Eigen::ArrayXd weights_of(std::initializer_list<double> values) {
  Eigen::ArrayXd w(static_cast<Eigen::Index>(values.size()));
  Eigen::Index i = 0;
  for (const double v : values) {
    w[i++] = v;
  }
  return w;
}

std::vector<int> copy_counts(const std::vector<std::size_t>& indices, Eigen::Index m) {
  std::vector<int> counts(static_cast<std::size_t>(m), 0);
  for (const std::size_t index : indices) {
    EXPECT_LT(index, static_cast<std::size_t>(m));
    ++counts[index];
  }
  return counts;
}

// ---- N_eff, eq. (6) ----

TEST(EffectiveSampleSize, UniformWeightsGiveM) {
  const Eigen::ArrayXd w = Eigen::ArrayXd::Constant(1000, 1.0 / 1000.0);
  EXPECT_NEAR(effective_sample_size(w), 1000.0, 1e-9);
}

TEST(EffectiveSampleSize, OneHotGivesOne) {
  Eigen::ArrayXd w = Eigen::ArrayXd::Zero(50);
  w[17] = 1.0;
  EXPECT_DOUBLE_EQ(effective_sample_size(w), 1.0);
}

TEST(EffectiveSampleSize, MatchesInverseSumOfSquares) {
  const Eigen::ArrayXd w = weights_of({0.1, 0.2, 0.3, 0.4});
  EXPECT_NEAR(effective_sample_size(w), 1.0 / (0.01 + 0.04 + 0.09 + 0.16), 1e-12);
  // Two equal halves: exactly two effective particles.
  EXPECT_NEAR(effective_sample_size(weights_of({0.5, 0.0, 0.5, 0.0})), 2.0, 1e-12);
}

TEST(EffectiveSampleSize, EmptyOrZeroIsZero) {
  EXPECT_EQ(effective_sample_size(Eigen::ArrayXd()), 0.0);
  EXPECT_EQ(effective_sample_size(Eigen::ArrayXd::Zero(4)), 0.0);
}

// ---- systematic ----

TEST(SystematicResample, PicksTheParticleUnderEachPointer) {
  // Cumulative 0.1, 0.3, 0.6, 1.0; pointers (0.24 + j) / 4 = 0.06, 0.31, 0.56, 0.81.
  const std::vector<std::size_t> indices =
      systematic_resample(weights_of({0.1, 0.2, 0.3, 0.4}), 0.24 / 4.0);
  EXPECT_EQ(indices, (std::vector<std::size_t>{0, 2, 2, 3}));
}

TEST(SystematicResample, OneHotCopiesThatParticle) {
  Eigen::ArrayXd w = Eigen::ArrayXd::Zero(8);
  w[3] = 1.0;
  for (const double u0 : {0.0, 0.06, 0.124999}) {
    EXPECT_EQ(systematic_resample(w, u0), std::vector<std::size_t>(8, 3));
  }
}

TEST(SystematicResample, NeverPicksZeroWeightParticlesEvenAtTheEdges) {
  const Eigen::ArrayXd w = weights_of({0.0, 0.3, 0.0, 0.7, 0.0});
  for (const double u0 : {0.0, 0.1, 0.2 - 1e-17, 0.2}) {  // 1/M itself is tolerated
    for (const std::size_t index : systematic_resample(w, u0)) {
      EXPECT_TRUE(index == 1 || index == 3) << "u0 = " << u0 << " picked " << index;
    }
  }
}

TEST(SystematicResample, AcceptsSlightlyUnnormalisedWeights) {
  const Eigen::ArrayXd w = weights_of({0.25, 0.25, 0.25, 0.25}) * (1.0 + 1e-12);
  EXPECT_EQ(systematic_resample(w, 0.125), (std::vector<std::size_t>{0, 1, 2, 3}));
}

TEST(SystematicResample, RejectsBadInput) {
  const Eigen::ArrayXd w = weights_of({0.5, 0.5});
  EXPECT_THROW(systematic_resample(w, -0.01), std::invalid_argument);
  EXPECT_THROW(systematic_resample(w, 0.51), std::invalid_argument);
  EXPECT_THROW(systematic_resample(w, std::numeric_limits<double>::quiet_NaN()),
               std::invalid_argument);
  EXPECT_THROW(systematic_resample(weights_of({0.5, -0.1}), 0.1), std::invalid_argument);
  EXPECT_THROW(systematic_resample(weights_of({0.0, 0.0}), 0.1), std::invalid_argument);
  EXPECT_THROW(systematic_resample(weights_of({std::numeric_limits<double>::quiet_NaN(), 1.0}), 0.1),
               std::invalid_argument);
  EXPECT_TRUE(systematic_resample(Eigen::ArrayXd(), 0.0).empty());
}

// ---- residual ----

TEST(ResidualResample, KeepsTheDeterministicCopies) {
  // M w = [2.4, 1.2, 0.4, 0]: floors 2 and 1 always, one more index drawn from the residuals.
  const Eigen::ArrayXd w = weights_of({0.6, 0.3, 0.1, 0.0});
  RandomEngine engine(11);
  for (int run = 0; run < 200; ++run) {
    const std::vector<int> counts = copy_counts(residual_resample(w, engine), 4);
    EXPECT_GE(counts[0], 2);
    EXPECT_GE(counts[1], 1);
    EXPECT_EQ(counts[3], 0);
    EXPECT_EQ(counts[0] + counts[1] + counts[2], 4);
  }
}

TEST(ResidualResample, DrawsOneUniformPerRemainderIndex) {
  // M w = [2.4, 1.2, 0.4, 0]: R = 1 draw.
  RandomEngine engine(5);
  RandomEngine reference(5);
  residual_resample(weights_of({0.6, 0.3, 0.1, 0.0}), engine);
  uniform01(reference);
  EXPECT_EQ(engine(), reference());
  // M w = [1, 2, 1, 0]: nothing left to draw, the result is deterministic.
  RandomEngine untouched(5);
  EXPECT_EQ(residual_resample(weights_of({0.25, 0.5, 0.25, 0.0}), untouched),
            (std::vector<std::size_t>{0, 1, 1, 2}));
  RandomEngine fresh(5);
  EXPECT_EQ(untouched(), fresh());
}

TEST(ResidualResample, RoundingDoesNotTurnAnExactSplitRandom) {
  // 500 of 1000 particles with weight 1/500: M w_i is 2 up to rounding, so exactly two copies
  // each and nothing drawn (a floor of 1.9999999999999998 would hand 500 copies to chance).
  Eigen::ArrayXd w = Eigen::ArrayXd::Zero(1000);
  w.head(500).setConstant(1.0 / 500.0);
  RandomEngine engine(8);
  RandomEngine fresh(8);
  const std::vector<int> counts = copy_counts(residual_resample(w, engine), 1000);
  for (Eigen::Index i = 0; i < 500; ++i) {
    ASSERT_EQ(counts[static_cast<std::size_t>(i)], 2) << "particle " << i;
  }
  EXPECT_EQ(engine(), fresh());
}

TEST(ResidualResample, RejectsBadWeights) {
  RandomEngine engine(1);
  EXPECT_THROW(residual_resample(weights_of({0.0, 0.0}), engine), std::invalid_argument);
  EXPECT_THROW(residual_resample(weights_of({1.0, -1.0, 1.0}), engine), std::invalid_argument);
  EXPECT_THROW(residual_resample(weights_of({std::numeric_limits<double>::infinity(), 1.0}), engine),
               std::invalid_argument);
}

// ---- properties shared by both schemes ----

using Resampler = std::function<std::vector<std::size_t>(const Eigen::ArrayXd&, RandomEngine&)>;

Resampler systematic() {
  return [](const Eigen::ArrayXd& w, RandomEngine& engine) {
    return systematic_resample(w, uniform01(engine) / static_cast<double>(w.size()));
  };
}

Resampler residual() {
  return [](const Eigen::ArrayXd& w, RandomEngine& engine) { return residual_resample(w, engine); };
}

class ResamplerProperties : public ::testing::TestWithParam<bool> {
 protected:
  Resampler resampler() const { return GetParam() ? residual() : systematic(); }
};

// Expected copy count of particle i over many runs must be M w_i (unbiasedness). Every run
// keeps at least floor(M w_i) copies; systematic also never exceeds ceil(M w_i).
TEST_P(ResamplerProperties, CopyCountsAreUnbiased) {
  const bool is_residual = GetParam();
  RandomEngine engine(is_residual ? 123 : 321);
  const Eigen::Index m = 40;
  Eigen::ArrayXd w(m);
  for (Eigen::Index i = 0; i < m; ++i) {
    // Mix of tiny, zero and large weights.
    w[i] = (i % 7 == 0) ? 0.0 : std::pow(uniform01(engine), 3.0);
  }
  w /= w.sum();

  const int runs = 40000;
  std::vector<double> mean_count(static_cast<std::size_t>(m), 0.0);
  const Resampler resample = resampler();
  for (int run = 0; run < runs; ++run) {
    const std::vector<std::size_t> indices = resample(w, engine);
    ASSERT_EQ(indices.size(), static_cast<std::size_t>(m));
    ASSERT_TRUE(std::is_sorted(indices.begin(), indices.end()));
    const std::vector<int> counts = copy_counts(indices, m);
    for (Eigen::Index i = 0; i < m; ++i) {
      const double expected = static_cast<double>(m) * w[i];
      const int count = counts[static_cast<std::size_t>(i)];
      ASSERT_GE(count, static_cast<int>(std::floor(expected))) << "particle " << i;
      if (!is_residual) {
        ASSERT_LE(count, static_cast<int>(std::ceil(expected))) << "particle " << i;
      }
      mean_count[static_cast<std::size_t>(i)] += count / static_cast<double>(runs);
    }
  }
  // The random part of a count is at most Binomial(R, r_i / R) with residual r_i < 1, so its
  // std is < 1 and the std of the mean over 40000 runs < 0.005; 0.025 is > 5 sigma.
  for (Eigen::Index i = 0; i < m; ++i) {
    EXPECT_NEAR(mean_count[static_cast<std::size_t>(i)], static_cast<double>(m) * w[i], 0.025)
        << "particle " << i;
  }
}

TEST_P(ResamplerProperties, UniformWeightsKeepEveryParticleOnce) {
  RandomEngine engine(9);
  const Eigen::ArrayXd w = Eigen::ArrayXd::Constant(64, 1.0 / 64.0);
  std::vector<std::size_t> identity(64);
  for (std::size_t i = 0; i < identity.size(); ++i) {
    identity[i] = i;
  }
  for (int run = 0; run < 20; ++run) {
    EXPECT_EQ(resampler()(w, engine), identity);
  }
}

// The two schemes must really differ: a systematic draw of the residual remainder would be
// identical to plain systematic resampling, which would make the option meaningless.
TEST(ResamplingSchemes, ResidualIsNotSystematicInDisguise) {
  const Eigen::ArrayXd w = weights_of({0.05, 0.13, 0.22, 0.27, 0.33});  // M w = .25 .65 1.1 1.35 1.65
  RandomEngine engine_a(4);
  RandomEngine engine_b(4);
  int differing_runs = 0;
  int residual_extra_copies = 0;
  for (int run = 0; run < 200; ++run) {
    const std::vector<std::size_t> from_residual = residual_resample(w, engine_a);
    const std::vector<std::size_t> from_systematic = systematic_resample(w, uniform01(engine_b) / 5.0);
    differing_runs += from_residual != from_systematic ? 1 : 0;
    // Multinomial remainder: sometimes more than ceil(M w_i) copies (impossible for systematic).
    const std::vector<int> counts = copy_counts(from_residual, 5);
    residual_extra_copies += counts[4] > 2 || counts[3] > 2 || counts[1] > 1 ? 1 : 0;
  }
  EXPECT_GT(differing_runs, 50);
  EXPECT_GT(residual_extra_copies, 0);
}

INSTANTIATE_TEST_SUITE_P(BothSchemes, ResamplerProperties, ::testing::Values(false, true),
                         [](const ::testing::TestParamInfo<bool>& info) {
                           return info.param ? "Residual" : "Systematic";
                         });

}  // namespace
}  // namespace robodds::pf_estimator
