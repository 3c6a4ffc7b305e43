#pragma once
// Issue 27, "missions degrade gracefully": what a robot that is steering does while its range-rate
// estimate is briefly unusable (an observer restart window, 0.5 s by default; a target switch the
// observer has not followed yet; not a stale one in real time: a silent observer may be dead).
// Stopping at once disturbed the formation at every restart: the law ramps back from rest at
// max_accel (0 to 13 m/s at 0.5 m/s^2: 26 s). Instead the robot keeps the curvature of its last
// command (the circle it was on, at lower speed), slows towards speed_fraction of that command's
// speed at most max_decel, and stops once the gap lasted longer than hold_s. Only a robot that
// steered at the step before the gap is held: a robot that was stopped stays stopped, and a gap
// that outlasts hold_s stops it until it steers again. Pure: std only, time in seconds.

#include <optional>

#include "common/model/twist.hpp"
#include "common/param_table.hpp"

namespace robodds::circumnavigation_controller {

// Units, ranges and descriptions: hold_param_table() (the one source); defaults: the initialisers.
struct HoldParams {
  double hold_s = 1.0;          // longest gap held, s (0: stop at once, as before issue 27)
  double speed_fraction = 0.5;  // the held speed tends to this fraction of the last command's

  /// Throws std::invalid_argument "key: requirement (got value)" for the first bad field.
  void validate() const;
};

const params::ParamTable<HoldParams>& hold_param_table();

class EstimateGapHold {
 public:
  /// Validates params (throws std::invalid_argument "key: ...").
  explicit EstimateGapHold(const HoldParams& params);

  /// The robot steered with `command` at this step (its estimate was usable): a gap that follows
  /// holds this command's curvature. Ends a gap.
  void steered(const model::Twist& command);
  /// The robot was stopped for another reason (no task, a mismatch of targets, ...): no hold until
  /// it steers again.
  void stopped();
  /// One step of dt_s (> 0) without a usable estimate: the command to hold, or nullopt (stop) when
  /// the robot was not steering before the gap, was not moving, or the gap has lasted longer than
  /// hold_s (then it stays nullopt until steered()). The speed moves towards speed_fraction |v|
  /// by at most max_decel_mps2 dt_s; omega keeps the last command's omega / v.
  std::optional<model::Twist> gap(double dt_s, double max_decel_mps2);

  /// In a gap and holding (the last gap() returned a command).
  bool holding() const { return holding_; }
  /// How long the current gap has lasted, s (0 outside a gap).
  double gap_s() const { return gap_s_; }

 private:
  HoldParams params_;
  bool armed_ = false;     // the robot steered at the step before: a gap may be held
  bool holding_ = false;
  model::Twist last_;      // the last command steered
  double speed_mps_ = 0.0; // the held speed now
  double gap_s_ = 0.0;
};

}  // namespace robodds::circumnavigation_controller
