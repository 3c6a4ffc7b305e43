// The UWB error model term by term: each term's standard deviation, mean and autocorrelation at
// its correlation time, in bands that a missing term or a wrong tau falls out of; what the two
// directions of a link share; NLOS rate and size; ranges >= 0; sigma_scale; seeding.
#include "components/uwb_sensor/uwb_error_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace robodds::uwb_sensor {
namespace {

const double kE1 = std::exp(-1.0);

UwbErrorParams only(double white, double bias, double common) {
  UwbErrorParams p;
  p.white_sigma_m = white;
  p.link_bias_sigma_m = bias;
  p.common_sigma_m = common;
  return p;
}

double mean(const std::vector<double>& x) {
  double s = 0.0;
  for (double v : x) {
    s += v;
  }
  return s / static_cast<double>(x.size());
}

double stddev(const std::vector<double>& x) {
  const double m = mean(x);
  double s = 0.0;
  for (double v : x) {
    s += (v - m) * (v - m);
  }
  return std::sqrt(s / static_cast<double>(x.size() - 1));
}

/// Sample autocorrelation of `x` at `lag` samples.
double autocorrelation(const std::vector<double>& x, std::size_t lag) {
  const double m = mean(x);
  double num = 0.0;
  double den = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    den += (x[i] - m) * (x[i] - m);
    if (i + lag < x.size()) {
      num += (x[i] - m) * (x[i + lag] - m);
    }
  }
  return num / den;
}

/// Pooled over `links` independent series (each autocorrelation averaged).
struct SeriesStats {
  double mean = 0.0;
  double std = 0.0;
  double rho_tau = 0.0;   // autocorrelation at the lag of tau
  double rho_one = 0.0;   // at one sample
};

SeriesStats stats_of(const std::vector<std::vector<double>>& series, std::size_t lag_tau) {
  SeriesStats s;
  std::vector<double> pooled;
  for (const auto& x : series) {
    pooled.insert(pooled.end(), x.begin(), x.end());
    s.rho_tau += autocorrelation(x, lag_tau) / static_cast<double>(series.size());
    s.rho_one += autocorrelation(x, 1) / static_cast<double>(series.size());
  }
  s.mean = mean(pooled);
  s.std = stddev(pooled);
  return s;
}

/// Errors r - d of `frames` frames of one direction, one series per link (k, l), 4 x 4 links,
/// sampled every dt_s; true range 10 m.
std::vector<std::vector<double>> error_series(const UwbErrorParams& p, double dt_s, std::size_t frames, std::uint64_t seed = 1) {
  PairErrors shared(4, 4, 0.0, p, RandomEngine(seed), RandomEngine(seed + 100));
  RandomEngine white(seed + 200);
  RandomEngine nlos(seed + 300);
  const Eigen::MatrixXd truth = Eigen::MatrixXd::Constant(4, 4, 10.0);
  std::vector<std::vector<double>> series(16);
  for (std::size_t f = 0; f < frames; ++f) {
    shared.advance_to(static_cast<double>(f) * dt_s);
    const Eigen::MatrixXd r = measure_ranges(truth, shared.link_bias_m(true), shared.common_m(), p, white, nlos);
    for (Eigen::Index i = 0; i < 16; ++i) {
      series[static_cast<std::size_t>(i)].push_back(r(i / 4, i % 4) - 10.0);
    }
  }
  return series;
}

// White noise only: std 0.04, mean 0, no correlation between frames.
TEST(UwbErrorModel, WhiteNoiseHasItsSigmaAndNoMemory) {
  const SeriesStats s = stats_of(error_series(only(0.04, 0.0, 0.0), 0.02, 5000), 1);
  EXPECT_NEAR(s.std, 0.04, 0.04 * 0.03);
  EXPECT_NEAR(s.mean, 0.0, 0.002);
  EXPECT_NEAR(s.rho_one, 0.0, 0.03);
}

// Link bias only: std 0.07, correlation e^-1 at tau = 2 s, independent links.
TEST(UwbErrorModel, LinkBiasIsGaussMarkovWithItsSigmaAndTau) {
  const double dt = 0.1;
  const auto series = error_series(only(0.0, 0.07, 0.0), dt, 100000);  // 10000 s, 5000 tau per link
  const SeriesStats s = stats_of(series, static_cast<std::size_t>(2.0 / dt));
  EXPECT_NEAR(s.std, 0.07, 0.07 * 0.05);
  EXPECT_NEAR(s.mean, 0.0, 0.006);
  EXPECT_NEAR(s.rho_tau, kE1, 0.05) << "tau 1 s would give 0.14, 4 s 0.61";
  // Links are independent of each other (not one bias for all).
  std::vector<double> diff;
  for (std::size_t i = 0; i < series[0].size(); ++i) {
    diff.push_back(series[0][i] - series[5][i]);
  }
  EXPECT_NEAR(stddev(diff), 0.07 * std::sqrt(2.0), 0.07 * 0.1);
}

// Common mode only: std 0.30, correlation e^-1 at tau = 10 s, the same on every link of a frame.
TEST(UwbErrorModel, CommonModeIsGaussMarkovSharedByAllLinksOfThePair) {
  const double dt = 1.0;
  const auto series = error_series(only(0.0, 0.0, 0.30), dt, 200000);  // 200000 s, 20000 tau
  const SeriesStats s = stats_of({series[0]}, static_cast<std::size_t>(10.0 / dt));
  EXPECT_NEAR(s.std, 0.30, 0.30 * 0.05);
  EXPECT_NEAR(s.mean, 0.0, 0.015);
  EXPECT_NEAR(s.rho_tau, kE1, 0.05) << "tau 5 s would give 0.14, 20 s 0.61";
  for (std::size_t i = 0; i < series[0].size(); i += 997) {
    EXPECT_EQ(series[0][i], series[15][i]) << "frame " << i;
  }
}

// All terms (defaults): total sigma sqrt(0.04^2 + 0.07^2 + 0.30^2); within one frame the common
// mode cancels between two links: sqrt(2 (0.04^2 + 0.07^2)). Either band fails without its term.
TEST(UwbErrorModel, DefaultsCombineTheTerms) {
  const auto series = error_series(UwbErrorParams{}, 1.0, 100000);
  const double total = std::sqrt(0.04 * 0.04 + 0.07 * 0.07 + 0.30 * 0.30);
  EXPECT_NEAR(stats_of({series[0]}, 1).std, total, total * 0.05);
  std::vector<double> diff;
  for (std::size_t i = 0; i < series[0].size(); ++i) {
    diff.push_back(series[0][i] - series[1][i]);
  }
  const double link = std::sqrt(2.0 * (0.04 * 0.04 + 0.07 * 0.07));
  EXPECT_NEAR(stddev(diff), link, link * 0.05) << "white 0.04 alone: 0.057; bias 0.07 alone: 0.099";
}

// The processes start stationary: the first value across seeds has the full sigma.
TEST(UwbErrorModel, StartsFromTheStationaryDistribution) {
  std::vector<double> common;
  std::vector<double> bias;
  for (std::uint64_t seed = 1; seed <= 4000; ++seed) {
    const PairErrors e(4, 4, 0.0, UwbErrorParams{}, RandomEngine(seed), RandomEngine(seed + 7777));
    common.push_back(e.common_m());
    bias.push_back(e.link_bias_m()(2, 3));
  }
  EXPECT_NEAR(stddev(common), 0.30, 0.30 * 0.05);
  EXPECT_NEAR(stddev(bias), 0.07, 0.07 * 0.05);
}

// Both directions of a pair measured at the same time differ only by their white noise and NLOS:
// link (k of a, l of b) seen from b is (l, k).
TEST(UwbErrorModel, BothDirectionsShareTheLinkBiasAndTheCommonMode) {
  const UwbErrorParams p;
  PairErrors shared(4, 4, 0.0, p, RandomEngine(1), RandomEngine(2));
  RandomEngine white_ab(3);
  RandomEngine white_ba(4);
  RandomEngine nlos_ab(5);
  RandomEngine nlos_ba(6);
  Eigen::MatrixXd truth(4, 4);
  for (Eigen::Index i = 0; i < 16; ++i) {
    truth(i / 4, i % 4) = 5.0 + 0.1 * static_cast<double>(i);
  }
  std::vector<double> diff;
  for (int f = 0; f < 5000; ++f) {
    shared.advance_to(0.1 * f);
    const Eigen::MatrixXd ab = measure_ranges(truth, shared.link_bias_m(true), shared.common_m(), p, white_ab, nlos_ab);
    shared.advance_to(0.1 * f);  // the second direction at the same time: no new draws
    const Eigen::MatrixXd ba = measure_ranges(truth.transpose(), shared.link_bias_m(false), shared.common_m(), p, white_ba, nlos_ba);
    for (Eigen::Index i = 0; i < 16; ++i) {
      diff.push_back(ab(i / 4, i % 4) - ba(i % 4, i / 4));
    }
  }
  EXPECT_NEAR(stddev(diff), 0.04 * std::sqrt(2.0), 0.04 * std::sqrt(2.0) * 0.05) << "only the white noise differs";
  EXPECT_NEAR(mean(diff), 0.0, 0.002);
}

TEST(UwbErrorModel, NlosExcessesHaveTheirRateAndRange) {
  UwbErrorParams p = only(0.0, 0.0, 0.0);
  p.nlos_probability = 0.1;
  const auto series = error_series(p, 0.02, 10000);
  std::size_t outliers = 0;
  std::size_t total = 0;
  double sum = 0.0;
  for (const auto& s : series) {
    for (double e : s) {
      ++total;
      if (e != 0.0) {
        ++outliers;
        sum += e;
        ASSERT_GE(e, 0.2 - 1e-9);  // r - d: rounding of 10 + o - 10
        ASSERT_LE(e, 1.5 + 1e-9);
      }
    }
  }
  const double rate = static_cast<double>(outliers) / static_cast<double>(total);
  EXPECT_NEAR(rate, 0.1, 0.005) << "160000 ranges: binomial sd 0.00075";
  EXPECT_NEAR(sum / static_cast<double>(outliers), 0.85, 0.01) << "uniform in [0.2, 1.5]";
  p.nlos_probability = 0.0;
  for (const auto& s : error_series(p, 0.02, 1000)) {
    for (double e : s) {
      ASSERT_EQ(e, 0.0);
    }
  }
}

// A wall in the way: every blocked link gets an excess in [min, max] at every frame, the others
// none (p = 0), and the draws are those of an open room (the streams do not shift).
TEST(UwbErrorModel, BlockedLinksAlwaysGetAnExcessAndTheDrawsStayTheSame) {
  const Eigen::MatrixXd truth = Eigen::MatrixXd::Constant(4, 4, 3.0);
  const Eigen::MatrixXd zero = Eigen::MatrixXd::Zero(4, 4);
  const UwbErrorParams p = only(0.0, 0.0, 0.0);
  BlockedLinks blocked = BlockedLinks::Constant(4, 4, false);
  blocked(0, 1) = true;
  blocked(3, 2) = true;
  RandomEngine white_a(9), white_b(9), nlos_a(10), nlos_b(10);
  for (int f = 0; f < 200; ++f) {
    const Eigen::MatrixXd r = measure_ranges(truth, zero, 0.0, p, white_a, nlos_a, blocked);
    const Eigen::MatrixXd open = measure_ranges(truth, zero, 0.0, p, white_b, nlos_b);
    for (Eigen::Index k = 0; k < 4; ++k) {
      for (Eigen::Index l = 0; l < 4; ++l) {
        const double excess = r(k, l) - 3.0;
        if (blocked(k, l)) {
          ASSERT_GE(excess, 0.2 - 1e-9);
          ASSERT_LE(excess, 1.5 + 1e-9);
        } else {
          ASSERT_NEAR(excess, 0.0, 1e-12);
        }
        ASSERT_NEAR(open(k, l), 3.0, 1e-12);
      }
    }
  }
  EXPECT_EQ(white_a, white_b);
  EXPECT_EQ(nlos_a, nlos_b);
}

// The NLOS and white streams advance by the same draws whatever p: the other draws do not shift.
TEST(UwbErrorModel, DrawsDoNotDependOnTheParameters) {
  const Eigen::MatrixXd truth = Eigen::MatrixXd::Constant(4, 4, 3.0);
  const Eigen::MatrixXd zero = Eigen::MatrixXd::Zero(4, 4);
  UwbErrorParams clean;
  UwbErrorParams noisy;
  noisy.nlos_probability = 0.5;
  noisy.white_sigma_m = 0.0;
  RandomEngine white_a(9);
  RandomEngine white_b(9);
  RandomEngine nlos_a(10);
  RandomEngine nlos_b(10);
  for (int f = 0; f < 100; ++f) {
    measure_ranges(truth, zero, 0.0, clean, white_a, nlos_a);
    measure_ranges(truth, zero, 0.0, noisy, white_b, nlos_b);
  }
  EXPECT_EQ(white_a, white_b);
  EXPECT_EQ(nlos_a, nlos_b);
  RandomEngine loss_a(11);
  RandomEngine loss_b(11);
  UwbErrorParams lossy;
  lossy.frame_loss_probability = 0.3;
  frame_lost(clean, loss_a);
  frame_lost(lossy, loss_b);
  EXPECT_EQ(loss_a, loss_b);
}

TEST(UwbErrorModel, RangesAreNeverNegative) {
  const Eigen::MatrixXd truth = Eigen::MatrixXd::Constant(4, 4, 0.05);
  PairErrors shared(4, 4, 0.0, UwbErrorParams{}, RandomEngine(1), RandomEngine(2));
  RandomEngine white(3);
  RandomEngine nlos(4);
  std::size_t clamped = 0;
  for (int f = 0; f < 2000; ++f) {
    shared.advance_to(0.1 * f);
    const Eigen::MatrixXd r = measure_ranges(truth, shared.link_bias_m(true), shared.common_m(), UwbErrorParams{}, white, nlos);
    ASSERT_GE(r.minCoeff(), 0.0) << "frame " << f;
    clamped += static_cast<std::size_t>((r.array() == 0.0).count());
  }
  EXPECT_GT(clamped, 1000u) << "0.05 m with 0.31 m errors: many would be negative unclamped";
}

// Same seeds: sigma_scale multiplies the whole error exactly (no NLOS, no clamping at 10 m).
TEST(UwbErrorModel, SigmaScaleScalesEverySigma) {
  UwbErrorParams scaled;
  scaled.sigma_scale = 1.25;
  const auto base = error_series(UwbErrorParams{}, 0.1, 2000);
  const auto more = error_series(scaled, 0.1, 2000);
  for (std::size_t l = 0; l < 16; ++l) {
    for (std::size_t f = 0; f < base[l].size(); f += 37) {
      ASSERT_NEAR(more[l][f], 1.25 * base[l][f], 1e-12) << "link " << l << " frame " << f;
    }
  }
  // And each term on its own: the white term's std.
  UwbErrorParams white = only(0.04, 0.0, 0.0);
  white.sigma_scale = 1.25;
  EXPECT_NEAR(stats_of(error_series(white, 0.02, 5000), 1).std, 0.05, 0.05 * 0.03);
}

TEST(UwbErrorModel, SameSeedsSameRangesOtherSeedsOthers) {
  const auto a = error_series(UwbErrorParams{}, 0.1, 50, 1);
  const auto b = error_series(UwbErrorParams{}, 0.1, 50, 1);
  const auto c = error_series(UwbErrorParams{}, 0.1, 50, 2);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
}

TEST(UwbErrorModel, FramesAreLostAtTheirRate) {
  UwbErrorParams p;
  RandomEngine loss(5);
  int lost = 0;
  for (int f = 0; f < 20000; ++f) {
    lost += frame_lost(p, loss) ? 1 : 0;
  }
  EXPECT_EQ(lost, 0);
  p.frame_loss_probability = 0.2;
  for (int f = 0; f < 20000; ++f) {
    lost += frame_lost(p, loss) ? 1 : 0;
  }
  EXPECT_NEAR(lost / 20000.0, 0.2, 0.015) << "binomial sd 0.0028";
}

TEST(UwbErrorParams, BadValuesNameTheKey) {
  UwbErrorParams p;
  p.link_bias_tau_s = 0.0;
  try {
    p.validate();
    FAIL() << "expected invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "link_bias_tau_s: must be > 0 and finite (got 0)");
  }
  p = UwbErrorParams{};
  p.nlos_min_m = 2.0;
  try {
    p.validate();
    FAIL() << "expected invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "nlos_min_m: must be <= nlos_max_m (1.5) (got 2)");
  }
  p = UwbErrorParams{};
  p.frame_loss_probability = 1.0;
  EXPECT_THROW(p.validate(), std::invalid_argument);
  EXPECT_NO_THROW(UwbErrorParams{}.validate());
}

}  // namespace
}  // namespace robodds::uwb_sensor
