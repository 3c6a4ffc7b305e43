#include "components/range_rate_observer/rate_uncertainty.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>

#include "common/random.hpp"

namespace robodds::range_rate_observer {
namespace {

constexpr double kRateHz = 50.0;

/// A range with a constant acceleration (0.4 m/s^2), sampled at 50 Hz with Gaussian noise noise_m.
double range_at(double t) { return 30.0 - 1.0 * t + 0.2 * t * t; }
double rate_at(double t) { return -1.0 + 0.4 * t; }

/// Feeds [from_s, to_s) with v_hat = true rate + error(t); returns the std at the end.
double feed(RateUncertainty& u, double from_s, double to_s, double noise_m, const std::function<double(double)>& error,
            RandomEngine& engine) {
  for (double t = from_s; t < to_s - 1e-9; t += 1.0 / kRateHz) {
    u.add(t, range_at(t) + noise_m * standard_normal(engine), rate_at(t) + error(t));
  }
  return u.std_mps();
}

TEST(RateUncertainty, ReportsTheStartStdUntilItsWindowIsFull) {
  RateUncertainty u;
  RandomEngine engine(1);
  u.restart(1.5);
  EXPECT_DOUBLE_EQ(u.std_mps(), 1.5);
  feed(u, 0.0, 1.9, 0.5, [](double) { return 0.0; }, engine);
  EXPECT_EQ(u.checks(), 0u);
  EXPECT_DOUBLE_EQ(u.std_mps(), 1.5);
}

TEST(RateUncertainty, AnExactEstimateIsReportedAtAboutTheSlopesOwnSpread) {
  // The check line's slope over 2 s of 0.5 m noise at 50 Hz has std 0.5 / sqrt(sum (t - tm)^2)
  // = 0.086 m/s: an exact estimate is reported at about that, not at the start's 2 m/s, and the
  // constant acceleration adds nothing (the quadratic term has no slope about the centre).
  RateUncertainty u;
  RandomEngine engine(2);
  u.restart(2.0);
  const double std_mps = feed(u, 0.0, 60.0, 0.5, [](double) { return 0.0; }, engine);
  EXPECT_GT(std_mps, 0.05);
  EXPECT_LT(std_mps, 0.13);
}

TEST(RateUncertainty, ABiasedEstimateIsReportedAtItsError) {
  RateUncertainty u;
  RandomEngine engine(3);
  u.restart(0.1);
  const double std_mps = feed(u, 0.0, 60.0, 0.5, [](double) { return 0.6; }, engine);
  EXPECT_GT(std_mps, 0.58);
  EXPECT_LT(std_mps, 0.7);
}

TEST(RateUncertainty, AGrowingErrorIsFollowedWithinTheCheckLagAndForgottenSlowly) {
  RateUncertainty u;
  RandomEngine engine(4);
  u.restart(0.1);
  feed(u, 0.0, 30.0, 0.2, [](double) { return 0.0; }, engine);
  const double before = u.std_mps();
  EXPECT_LT(before, 0.1);
  // The error jumps to 1 m/s at 30 s: the check sees it 1 s later (half its window), and the fast
  // mean (0.5 s) has it after another second.
  feed(u, 30.0, 32.0, 0.2, [](double) { return 1.0; }, engine);
  EXPECT_GT(u.std_mps(), 0.75);
  // Gone again: 3 s later the slow mean (5 s) still remembers it.
  feed(u, 32.0, 35.0, 0.2, [](double) { return 0.0; }, engine);
  EXPECT_GT(u.std_mps(), 0.25);
}

TEST(RateUncertainty, ANoisyEstimateIsRarelyOutsideThreeReportedStds) {
  // An estimate whose error is a slowly varying Gaussian process (an AR(1) with a 1 s time
  // constant, std 0.3 m/s), as an observer's is: outside 3 reported stds in well under 1 % of
  // the samples once checked (a consistent Gaussian report: 0.27 %).
  RateUncertainty u;
  RandomEngine engine(5);
  u.restart(2.0);
  double e = 0.0;
  const double keep = std::exp(-1.0 / kRateHz);
  int outside = 0, judged = 0;
  for (double t = 0.0; t < 600.0; t += 1.0 / kRateHz) {
    e = keep * e + std::sqrt(1.0 - keep * keep) * 0.3 * standard_normal(engine);
    u.add(t, range_at(t) + 0.5 * standard_normal(engine), rate_at(t) + e);
    if (t > 10.0) {
      ++judged;
      outside += std::abs(e) > 3.0 * u.std_mps() ? 1 : 0;
    }
  }
  EXPECT_LT(static_cast<double>(outside) / judged, 0.01) << outside << " of " << judged;
  EXPECT_GT(u.std_mps(), 0.2);  // not uselessly wide either: about the 0.3 m/s it is
  EXPECT_LT(u.std_mps(), 0.5);
}

TEST(RateUncertainty, RejectsBadParametersNamingThem) {
  const auto message = [](RateUncertaintyParams p) {
    try {
      RateUncertainty u(p);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  RateUncertaintyParams p;
  p.check_window_s = 0.0;
  EXPECT_NE(message(p).find("check_window_s"), std::string::npos) << message(p);
  p = {};
  p.slow_tau_s = NAN;
  EXPECT_NE(message(p).find("slow_tau_s"), std::string::npos) << message(p);
  p = {};
  p.initial_rate_std_mps = -1.0;
  EXPECT_NE(message(p).find("initial_rate_std_mps"), std::string::npos) << message(p);
  p = {};
  p.range_accel_mps2 = -0.5;
  EXPECT_NE(message(p).find("range_accel_mps2"), std::string::npos) << message(p);
}

}  // namespace
}  // namespace robodds::range_rate_observer
