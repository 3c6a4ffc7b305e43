#pragma once
// Which samples of a stream a lockstep reader will ever read, so that across processes the
// writer sends it only those (a content filter Fast DDS evaluates writer-side; runtime/dds).
//
// A consumer due every p steps that reads d steps late reads, at its due step k, the newest
// sample with step <= k - d: it reads at the "read steps" m = k - d, m = -d (mod p). A sample
// announces the step of the next one of its instance (SampleHeader::next_step, n): it is the
// newest at every read step in [step, n), and at no other. So the sample is needed exactly when
// [step, n) holds a read step. A 10 Hz sensor of a 100 Hz plant needs one state in ten.
// Pure: counts of steps.

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace robodds {

class StepNeeds {
 public:
  /// Every sample (no stride).
  StepNeeds() = default;
  /// The read steps of a component due every `period_steps` (>= 1) that also waits for its inputs
  /// every `checkpoint_steps` (0: never; runtime/lockstep/history_checkpoints.hpp), reading
  /// `delay_steps` late.
  static StepNeeds of_component(std::uint64_t period_steps, std::uint64_t checkpoint_steps, std::uint64_t delay_steps);

  /// Every sample is needed.
  bool all() const { return strides_.empty(); }
  /// Whether a sample of step `step` whose next comes at `next_step` is needed. One whose header
  /// is inconsistent (next_step <= step) is: the reader's checks count it.
  bool needs(std::uint64_t step, std::uint64_t next_step) const;
  /// The first read step >= `from` (`from` itself when every sample is needed).
  std::uint64_t first_read_step_from(std::uint64_t from) const;

  /// The needs of several subscribers of one reader: a sample any of them needs.
  void add(const StepNeeds& other);

  /// "steps" followed by " period:residue" per stride, e.g. "steps 10:0" (read steps m = 0 mod 10);
  /// "steps" alone: every sample. A content filter's expression; parse() reads it back.
  std::string text() const;
  /// text()'s inverse; nullopt when `text` is not one (a period of 0, a residue >= its period,
  /// anything else): the caller names the source.
  static std::optional<StepNeeds> parse(const std::string& text);

  bool operator==(const StepNeeds& other) const { return strides_ == other.strides_; }

 private:
  void add_stride(std::uint64_t period, std::uint64_t residue);
  // (period, residue): read steps m = residue (mod period); sorted, no duplicates, period >= 2
  // (a period of 1 needs every sample). Empty: every sample.
  std::vector<std::pair<std::uint64_t, std::uint64_t>> strides_;
};

}  // namespace robodds
