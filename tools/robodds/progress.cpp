#include "tools/robodds/progress.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "tools/robodds/run_report.hpp"

namespace robodds {

bool ProgressPacer::due(std::uint64_t done, std::uint64_t total, double wall_s) {
  if (finished_) {
    return false;
  }
  if (done >= total) {
    finished_ = true;
    return true;
  }
  if (terminal_) {
    if (wall_s - last_print_s_ < kTerminalPeriodS) {
      return false;
    }
    last_print_s_ = wall_s;
    return true;
  }
  // 10 % more since the last line, or 30 s later: whichever comes first.
  const bool tenth_more = static_cast<double>(done - std::min(done, last_done_)) >= kPipedFraction * static_cast<double>(total);
  if (!tenth_more && wall_s - last_print_s_ < kPipedPeriodS) {
    return false;
  }
  last_done_ = done;
  last_print_s_ = wall_s;
  return true;
}

std::string clock_text(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0.0) {
    return "--:--";
  }
  const long long total = std::llround(seconds);
  char text[48];
  if (total >= 3600) {
    std::snprintf(text, sizeof text, "%lld:%02lld:%02lld", total / 3600, total / 60 % 60, total % 60);
  } else {
    std::snprintf(text, sizeof text, "%lld:%02lld", total / 60, total % 60);
  }
  return text;
}

std::string eta_text(std::uint64_t done, std::uint64_t total, double wall_s) {
  if (done == 0 || done > total) {
    return "ETA --:--";
  }
  return "ETA " + clock_text(wall_s / static_cast<double>(done) * static_cast<double>(total - done));
}

std::string run_progress_text(std::uint64_t step, std::uint64_t last_step, double step_s, double wall_s) {
  const double percent = last_step > 0 ? 100.0 * static_cast<double>(step) / static_cast<double>(last_step) : 100.0;
  const double sim_s = static_cast<double>(step) * step_s;
  std::string text = "step " + std::to_string(step) + " / " + std::to_string(last_step) + " (" +
                     std::to_string(static_cast<int>(percent)) + " %), " + round_significant(sim_s, 4) + " of " +
                     round_significant(static_cast<double>(last_step) * step_s, 4) + " s simulated";
  if (wall_s > 0.0 && step > 0) {
    text += ", " + round_significant(sim_s / wall_s, 3) + "x real time";
  }
  return text + ", " + eta_text(step, last_step, wall_s);
}

std::string replay_progress_text(std::uint64_t done, std::uint64_t total, double recorded_s, double span_s, double wall_s) {
  std::string text = "message " + std::to_string(done) + " / " + std::to_string(total) + " (" +
                     std::to_string(total > 0 ? done * 100 / total : 100) + " %), " + round_significant(recorded_s, 4) + " of " +
                     round_significant(span_s, 4) + " s of the recording";
  if (wall_s > 0.0 && recorded_s > 0.0) {
    text += ", " + round_significant(recorded_s / wall_s, 3) + "x recorded speed";
  }
  return text + ", " + eta_text(done, total, wall_s);
}

std::string progress_output(const std::string& text, bool terminal, bool last) {
  if (!terminal) {
    return text + "\n";
  }
  return "\r" + text + "\033[K" + (last ? "\n" : "");
}

}  // namespace robodds
