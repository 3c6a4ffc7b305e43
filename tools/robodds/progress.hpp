#pragma once
// Progress of long commands (`robodds run`, `robodds sweep`, `robodds replay`) on stderr: on a
// terminal one line rewritten in place, at most every 0.2 s; piped (CI logs, containers) one
// line per 10 % or every 30 s, whichever comes first. Pure: the caller gives the wall clock.

#include <cstdint>
#include <string>

namespace robodds {

/// When to print.
class ProgressPacer {
 public:
  static constexpr double kTerminalPeriodS = 0.2;  // a live line faster than this only flickers
  static constexpr double kPipedPeriodS = 30.0;    // a CI log shows life at least this often
  static constexpr double kPipedFraction = 0.1;    // and a line per 10 % of the work

  explicit ProgressPacer(bool terminal) : terminal_(terminal) {}
  /// True when the progress `done` of `total` at `wall_s` (s since the start) is to be printed;
  /// the last one (done == total) always, once.
  bool due(std::uint64_t done, std::uint64_t total, double wall_s);
  bool terminal() const { return terminal_; }

 private:
  bool terminal_;
  double last_print_s_ = 0.0;
  std::uint64_t last_done_ = 0;
  bool finished_ = false;
};

/// "0:42", "12:03", "1:02:03" (rounded to the second; "--:--" when not finite or negative).
std::string clock_text(double seconds);

/// The remaining wall time at this pace: "ETA 1:02", "ETA --:--" before anything is done.
std::string eta_text(std::uint64_t done, std::uint64_t total, double wall_s);

/// A run's progress: "step 12000 / 35000 (34 %), 120 of 350 s simulated, 195x real time, ETA 0:02".
std::string run_progress_text(std::uint64_t step, std::uint64_t last_step, double step_s, double wall_s);

/// A replay's progress: "message 1200 / 5000 (24 %), 12 of 50 s of the recording, 3.1x recorded
/// speed, ETA 0:12".
std::string replay_progress_text(std::uint64_t done, std::uint64_t total, double recorded_s, double span_s, double wall_s);

/// `text` as written to stderr: on a terminal "\r" + text + clear-to-end-of-line, a newline only
/// after the last; piped text + newline.
std::string progress_output(const std::string& text, bool terminal, bool last);

}  // namespace robodds
