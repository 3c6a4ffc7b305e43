// robodds-observer-study: the observer study of issue 10 as a CSV (observer_study.hpp).
//   robodds-observer-study [--seeds N] [--duration full|short|SECONDS] [--out FILE]
// Not installed; scripts/paper2_observer_study.sh runs it and draws the figure.

#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
#include <exception>
#include <fstream>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <string>

#include "common/number_parse.hpp"
#include "components/range_rate_observer/study/observer_study.hpp"

namespace {

/// "full" 200 s, "short" 40 s (the smoke test), or a number of seconds.
double duration_from_text(const std::string& text) {
  if (text == "full") {
    return 200.0;
  }
  if (text == "short") {
    return 40.0;
  }
  const std::optional<double> seconds = robodds::parse_finite_number(text);
  if (!seconds) {
    throw std::invalid_argument("--duration: expected full, short or seconds (got " + text + ")");
  }
  return *seconds;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Lag against noise floor of paper 2's range-rate observers and the Kalman filter over seeds, noise "
               "levels, sample rates, linear gains and Kalman q; prints a CSV."};
  std::size_t seeds = 20;
  std::string duration = "full";
  std::string out_path;
  app.add_option("--seeds", seeds, "seeds per case (>= 1)")->capture_default_str();
  app.add_option("--duration", duration, "full (200 s), short (40 s) or seconds; the first 20 s are skipped")
      ->capture_default_str();
  app.add_option("--out", out_path, "write the CSV here instead of stdout");
  CLI11_PARSE(app, argc, argv);
  try {
    robodds::range_rate_observer::study::StudyOptions options;
    options.seeds = seeds;
    options.duration_s = duration_from_text(duration);
    const auto start = std::chrono::steady_clock::now();
    const auto rows = robodds::range_rate_observer::study::run_study(options);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (out_path.empty()) {
      robodds::range_rate_observer::study::write_csv(std::cout, rows);
    } else {
      std::ofstream out(out_path);
      if (!out) {
        throw std::runtime_error("--out: cannot write " + out_path);
      }
      robodds::range_rate_observer::study::write_csv(out, rows);
      if (!out.flush()) {
        throw std::runtime_error("--out: write failed: " + out_path);
      }
    }
    std::fprintf(stderr, "robodds-observer-study: %zu rows, %zu seeds, %.1f s\n", rows.size(), seeds, seconds);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "robodds-observer-study: error: %s\n", error.what());
    return 2;
  }
  return 0;
}
