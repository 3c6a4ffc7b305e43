#pragma once
// How a component subscribes (Subscription: which instances, how many steps late) and how the
// runtime sets an Input up from it (detail::InputOptions).

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace robodds {

/// What a component chooses when it subscribes: which instances it needs and how many steps
/// late it reads them, e.g.
///   ctx.subscribe<Msg>("some/topic", Subscription::instances(ctx.robot_keys()).delayed(1))
/// (docs/writing-a-component.md shows the robot system's).
class Subscription {
 public:
  /// Needs these instances (instance_key values, e.g. robot ids from ctx.robot_keys()) at every
  /// due step: in lockstep the component runs only once each has delivered up to the step it
  /// reads. Samples of other instances are ignored. An empty list is any_instance().
  static Subscription instances(std::vector<std::uint64_t> keys) {
    Subscription s;
    s.expected_ = std::move(keys);
    return s;
  }
  /// For topics keyed (robot_id, X) whose robot moves from one X to another (e.g. X a target that
  /// a mission event changes): these robot ids, and
  /// per robot ONE stream whatever its X. In lockstep the component waits, per robot, for the
  /// newest sample of any X, so a producer that switches a robot from (r, 1) to (r, 2) at step S
  /// is waited for at S without the consumer knowing the new X in advance. Read with
  /// Input::latest_of_robot() / take_new_of_robot(). A producer ends a robot's stream with
  /// publish_final() (e.g. the robot leaves the mission).
  static Subscription robot_streams(std::vector<std::uint64_t> robot_ids) {
    Subscription s = instances(std::move(robot_ids));
    s.by_robot_ = true;
    return s;
  }
  /// Takes every instance and waits for none: reads whatever has arrived, which is not
  /// deterministic across deployments (monitoring only).
  static Subscription any_instance() { return Subscription{}; }
  /// Reads samples of step <= m - steps at step m (1 closes a loop: a consumer acts on what its
  /// producer computed at the previous step). Default 0.
  Subscription delayed(std::uint64_t steps) const {
    Subscription s = *this;
    s.delay_steps_ = steps;
    return s;
  }

  const std::vector<std::uint64_t>& expected() const { return expected_; }
  std::uint64_t delay_steps() const { return delay_steps_; }
  bool by_robot() const { return by_robot_; }
  bool reads_newest_only() const { return newest_only_; }

  /// Reads only the newest sample of each instance at its due steps (Input::latest(), never
  /// take_new(), which then throws): in lockstep across processes the writers send it only the
  /// samples it will read (runtime/bus/step_needs.hpp), e.g. one state in ten for a 10 Hz sensor
  /// of a 100 Hz plant. Not with robot_streams().
  Subscription newest_only() const {
    Subscription s = *this;
    s.newest_only_ = true;
    return s;
  }

 private:
  Subscription() = default;
  std::vector<std::uint64_t> expected_;
  std::uint64_t delay_steps_ = 0;
  bool by_robot_ = false;
  bool newest_only_ = false;
};

namespace detail {

/// Runtime-internal (components use Subscription): how an Input is set up.
/// ComponentContext::subscribe() builds it from a Subscription and the topic catalog; the host
/// builds its tick/ack inputs directly.
struct InputOptions {
  /// Instances (instance_key values) needed at every due step; empty: every instance, gate on none.
  std::vector<std::uint64_t> expected;
  /// Read samples of step <= m - delay_steps.
  std::uint64_t delay_steps = 0;
  /// Host-level inputs (ticks, acks) see every sample regardless of the component's step.
  bool ignore_step = false;
  /// Subscription::robot_streams(): `expected` holds robot ids, and readiness and producers are
  /// tracked per robot id (the key's upper 32 bits), whatever the second key part.
  bool by_robot = false;
  /// Subscription::newest_only(): the component reads only latest() at its due steps.
  bool newest_only = false;
  /// The topic's key field names (from the topic catalog), used in error messages.
  std::string key_names;
  /// Labels for instances whose key cannot be spelled from key_names (e.g. hashed strings).
  std::map<std::uint64_t, std::string> labels;
  /// Spells SampleMeta::writer_id in log lines (Bus::writer_name); empty: "writer <id>".
  std::function<std::string(std::uint64_t)> writer_name;
  /// The topic's endpoints use DDS exclusive ownership (a hot standby writes it): the middleware
  /// picks the writer, and a change of writer is a logged hand-over, not a second producer.
  bool exclusive_ownership = false;
  /// A send-once topic (a mission): its producer is never "silent", so no other writer takes an
  /// instance over for want of samples.
  bool send_once = false;
  /// A scenario run: whether writer `writer_id` may produce the instances of robot `robot` (an
  /// unkeyed topic: 0): its process runs a component the scenario assigns to them (or the
  /// scenario assigns none: then any writer may, the first one wins). Every other writer is
  /// refused and counted as unknown_producer, whenever it starts. Empty: the first writer of an
  /// instance is its producer.
  std::function<bool(std::uint64_t writer_id, std::uint32_t robot)> producer_assigned;
  /// The scenario's robot ids: a sample whose key names another robot is refused and counted as
  /// unknown_key without any per-instance state (a flood of keys costs nothing to keep). Empty:
  /// every key is known.
  std::vector<std::uint32_t> known_robots;
};

}  // namespace detail

}  // namespace robodds
