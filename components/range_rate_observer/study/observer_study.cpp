#include "components/range_rate_observer/study/observer_study.hpp"

#include <cmath>
#include <cstdio>
#include <ostream>
#include <stdexcept>
#include <string>

#include "common/random.hpp"
#include "components/range_rate_observer/range_rate_observer.hpp"

namespace robodds::range_rate_observer::study {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kBaseRangeM = 300.0;
constexpr double kOrbitAmplitudeM = 60.0;
constexpr double kOrbitRateRadps = 0.15;
constexpr double kApproachMps = -8.0;
constexpr double kAccelerationMps2 = 1.0;

template <class Observer>
RunResult run(Observer observer, Observer default_jump_copy, const RangeSignal& signal, const RunSpec& spec) {
  RandomEngine engine(spec.noise_seed);
  const long samples = std::lround(spec.duration_s * spec.rate_hz);
  double sum_sq = 0.0;
  double sum = 0.0;
  long count = 0;
  for (long k = 0; k <= samples; ++k) {
    const double t = static_cast<double>(k) / spec.rate_hz;
    const double range = signal.range_m(t) + spec.sigma_m * standard_normal(engine);
    const RangeRateEstimate estimate = observer.update(t, range);
    default_jump_copy.update(t, range);
    if (t >= spec.steady_from_s) {
      const double error = estimate.rate_mps - signal.rate_mps(t);
      sum_sq += error * error;
      sum += error;
      ++count;
    }
  }
  RunResult result;
  result.rms_error_mps = count > 0 ? std::sqrt(sum_sq / static_cast<double>(count)) : 0.0;
  result.mean_error_mps = count > 0 ? sum / static_cast<double>(count) : 0.0;
  result.restarts_at_default_jump = default_jump_copy.restarts();
  return result;
}

std::string number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.5g", value);
  return buffer;
}

}  // namespace

const char* observer_name(ObserverKind kind) {
  switch (kind) {
    case ObserverKind::kSuperTwisting:
      return "sta";
    case ObserverKind::kLinear:
      return "linear";
    case ObserverKind::kKalman:
      return "kf";
  }
  return "?";
}

const char* signal_name(SignalKind kind) {
  switch (kind) {
    case SignalKind::kOrbit:
      return "orbit";
    case SignalKind::kConstantAcceleration:
      return "accel";
    case SignalKind::kConstant:
      return "constant";
  }
  return "?";
}

double RangeSignal::range_m(double t_s) const {
  switch (kind) {
    case SignalKind::kOrbit:
      return kBaseRangeM + kOrbitAmplitudeM * std::sin(kOrbitRateRadps * t_s + phase_rad);
    case SignalKind::kConstantAcceleration:
      return kBaseRangeM + kApproachMps * t_s + 0.5 * kAccelerationMps2 * t_s * t_s;
    case SignalKind::kConstant:
      return kBaseRangeM;
  }
  return kBaseRangeM;
}

double RangeSignal::rate_mps(double t_s) const {
  switch (kind) {
    case SignalKind::kOrbit:
      return kOrbitAmplitudeM * kOrbitRateRadps * std::cos(kOrbitRateRadps * t_s + phase_rad);
    case SignalKind::kConstantAcceleration:
      return kApproachMps + kAccelerationMps2 * t_s;
    case SignalKind::kConstant:
      return 0.0;
  }
  return 0.0;
}

ObserverConfig super_twisting_config() {
  ObserverConfig config;
  config.kind = ObserverKind::kSuperTwisting;
  config.sta.restart_sigmas = 0.0;
  return config;
}

ObserverConfig linear_config(double w_radps) {
  ObserverConfig config;
  config.kind = ObserverKind::kLinear;
  config.w_radps = w_radps;
  config.linear.k1 = 2.0 * w_radps;
  config.linear.k2 = w_radps * w_radps;
  config.linear.restart_sigmas = 0.0;
  return config;
}

ObserverConfig kalman_config(double q_m2ps5) {
  ObserverConfig config;
  config.kind = ObserverKind::kKalman;
  config.kalman.jerk_psd_m2ps5 = q_m2ps5;
  config.kalman.restart_sigmas = 0.0;
  return config;
}

RunResult run_observer(const ObserverConfig& observer, const RangeSignal& signal, const RunSpec& spec) {
  switch (observer.kind) {
    case ObserverKind::kSuperTwisting: {
      SuperTwistingParams with_jump = observer.sta;
      with_jump.restart_sigmas = SuperTwistingParams{}.restart_sigmas;
      return run(SuperTwistingObserver(observer.sta), SuperTwistingObserver(with_jump), signal, spec);
    }
    case ObserverKind::kLinear: {
      LinearObserverParams with_jump = observer.linear;
      with_jump.restart_sigmas = LinearObserverParams{}.restart_sigmas;
      return run(LinearRangeRateObserver(observer.linear), LinearRangeRateObserver(with_jump), signal, spec);
    }
    case ObserverKind::kKalman: {
      KalmanObserverParams with_jump = observer.kalman;
      with_jump.restart_sigmas = KalmanObserverParams{}.restart_sigmas;
      return run(KalmanRangeRateObserver(observer.kalman), KalmanRangeRateObserver(with_jump), signal, spec);
    }
  }
  throw std::invalid_argument("observer study: unknown observer kind");
}

std::vector<StudyRow> run_study(const StudyOptions& options) {
  if (options.seeds < 1) {
    throw std::invalid_argument("observer study: seeds must be >= 1");
  }
  if (!(options.steady_from_s < options.duration_s)) {
    throw std::invalid_argument("observer study: duration_s must exceed steady_from_s (" +
                                std::to_string(options.steady_from_s) + " s)");
  }
  std::vector<ObserverConfig> observers = {super_twisting_config()};
  for (double w : options.linear_w_radps) {
    observers.push_back(linear_config(w));
  }
  for (double q : options.kalman_q_m2ps5) {
    observers.push_back(kalman_config(q));
  }
  std::vector<StudyRow> rows;
  for (SignalKind kind : options.signals) {
    for (double rate_hz : options.rates_hz) {
      for (double sigma_m : options.sigmas_m) {
        for (const ObserverConfig& observer : observers) {
          std::vector<double> lag;
          std::vector<double> noise;
          std::vector<double> total;
          double restarts = 0.0;
          double bias = 0.0;
          for (std::size_t seed = 1; seed <= options.seeds; ++seed) {
            RangeSignal signal{kind, 0.0};
            if (kind == SignalKind::kOrbit) {
              RandomEngine phase_engine(derive_seed(seed, "observer_study/phase"));
              signal.phase_rad = 2.0 * kPi * uniform01(phase_engine);
            }
            RunSpec spec{rate_hz, options.duration_s, options.steady_from_s, 0.0,
                         derive_seed(seed, std::string("observer_study/noise/") + signal_name(kind))};
            lag.push_back(run_observer(observer, signal, spec).rms_error_mps);
            spec.sigma_m = sigma_m;
            const RunResult noisy = run_observer(observer, signal, spec);
            total.push_back(noisy.rms_error_mps);
            bias += noisy.mean_error_mps;
            restarts += static_cast<double>(noisy.restarts_at_default_jump);
            spec.noise_seed = derive_seed(seed, "observer_study/noise/constant");
            noise.push_back(run_observer(observer, RangeSignal{SignalKind::kConstant, 0.0}, spec).rms_error_mps);
          }
          StudyRow row;
          row.signal = kind;
          row.rate_hz = rate_hz;
          row.sigma_m = sigma_m;
          row.observer = observer;
          row.seeds = options.seeds;
          row.lag_mps = stats::summarize(lag);
          row.noise_mps = stats::summarize(noise);
          row.total_mps = stats::summarize(total);
          row.total_bias_mps = bias / static_cast<double>(options.seeds);
          row.restarts_per_run = restarts / static_cast<double>(options.seeds);
          rows.push_back(row);
        }
      }
    }
  }
  return rows;
}

void write_csv(std::ostream& out, const std::vector<StudyRow>& rows) {
  out << "signal,rate_hz,sigma_m,observer,w_radps,k1,k2,q_m2ps5,seeds,lag_rms_mps,lag_ci95_mps,noise_rms_mps,"
         "noise_ci95_mps,total_rms_mps,total_ci95_mps,total_bias_mps,restarts_per_run\n";
  for (const StudyRow& row : rows) {
    const ObserverConfig& o = row.observer;
    out << signal_name(row.signal) << ',' << number(row.rate_hz) << ',' << number(row.sigma_m) << ','
        << observer_name(o.kind) << ',';
    if (o.kind == ObserverKind::kLinear) {
      out << number(o.w_radps) << ',' << number(o.linear.k1) << ',' << number(o.linear.k2);
    } else {
      out << ",,";
    }
    out << ',';
    if (o.kind == ObserverKind::kKalman) {
      out << number(o.kalman.jerk_psd_m2ps5);
    }
    out << ',' << row.seeds << ',' << number(row.lag_mps.mean) << ',' << number(row.lag_mps.ci95) << ','
        << number(row.noise_mps.mean) << ',' << number(row.noise_mps.ci95) << ',' << number(row.total_mps.mean)
        << ',' << number(row.total_mps.ci95) << ',' << number(row.total_bias_mps) << ','
        << number(row.restarts_per_run) << '\n';
  }
}

}  // namespace robodds::range_rate_observer::study
