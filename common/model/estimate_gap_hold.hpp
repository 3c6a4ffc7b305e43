#pragma once
// Issue 27, "missions degrade gracefully": what a robot that is driving does while its estimate is
// briefly unusable: the estimate arrives but says it is not valid (paper 2: an observer restart
// window, a target switch the observer has not followed yet; paper 1: a particle filter whose
// spread is momentarily too wide, or one redrawn from the fixes). Not a stale estimate, nor one
// whose producer says its own inputs went stale: a silent producer may be dead, and the freshness
// rules of issue 24 stop the robot. Stopping at once costs the whole ramp back from rest (paper 2:
// 0 to 13 m/s at 0.5 m/s^2, 26 s; paper 1: a stop at every flicker of `valid`). Instead the robot
// keeps the curvature of its last command (the arc it was on, at lower speed), slows towards
// speed_fraction of that command's speed at most max_decel, and stops once the gap lasted longer
// than hold_s. Only a robot that was driven by its controller at the step before the gap is held: a
// robot that was stopped stays stopped, and a gap that outlasts hold_s stops it until it is driven
// again. Shared by the circumnavigation and the way-point controllers. Pure: std only, seconds.

#include <optional>

#include "common/model/twist.hpp"
#include "common/param_table.hpp"

namespace robodds::model {

// Units, ranges and descriptions: hold_param_table() (the one source); defaults: the initialisers.
// Each controller includes the table under its key gap_hold.
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

  /// The controller drove the robot with `command` at this step (its estimate was usable): a gap
  /// that follows holds this command's curvature. Ends a gap.
  void steered(const Twist& command);
  /// The robot was stopped for another reason (no task, a stale estimate, the mission done, ...):
  /// no hold until it is steered again.
  void stopped();
  /// One step of dt_s (> 0) without a usable estimate: the command to hold, or nullopt (stop) when
  /// the robot was not steered before the gap, was not moving (v = 0), or the gap has lasted longer
  /// than hold_s (then it stays nullopt until steered()). The speed moves towards
  /// speed_fraction * v by at most max_decel_mps2 * dt_s (max_decel_mps2 <= 0: no limit, at once);
  /// omega keeps the last command's omega / v (a robot backing up keeps backing up, slower).
  std::optional<Twist> gap(double dt_s, double max_decel_mps2);

  /// In a gap and holding (the last gap() returned a command).
  bool holding() const { return holding_; }
  /// How long the current gap has lasted, s (0 outside a gap).
  double gap_s() const { return gap_s_; }
  const HoldParams& params() const { return params_; }

 private:
  HoldParams params_;
  bool armed_ = false;     // the robot was steered at the step before: a gap may be held
  bool holding_ = false;
  Twist last_;             // the last command steered
  double speed_mps_ = 0.0; // the held speed now
  double gap_s_ = 0.0;
};

}  // namespace robodds::model
