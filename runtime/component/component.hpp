#pragma once
// The component model. A component is a class registered by type name; it has no main and
// does not know how it is deployed. The host configures it once (parameters, inputs, outputs,
// rate) and then calls on_step() at each due step on the host's executor thread.

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "runtime/bus/bus.hpp"
#include "runtime/health/compute_times.hpp"
#include "runtime/base/error.hpp"
#include "runtime/health/host_health.hpp"
#include "runtime/base/log.hpp"
#include "runtime/io/io.hpp"
#include "runtime/config/params.hpp"
#include "runtime/config/scenario.hpp"
#include "runtime/topics/topic_catalog.hpp"

namespace robodds {

struct StepInfo {
  std::uint64_t step = 0;  // the due step
  double time_s = 0.0;     // sim time (lockstep) or seconds since start (real-time)
  double dt_s = 0.0;       // s since this component's previous step (its period in lockstep)
  std::int64_t stamp_ns = 0;  // the stamp its samples get: sim time (lockstep) or wall clock (real time)
};

class ComponentContext;

/// What a component assumes of the rate of an input's producer: declared at configure
/// (ComponentContext::expects_rate_of(), limits_age_of()) and checked before the run against the
/// scenario's producers (check_input_rates(), runtime/host/producer_check.hpp), since no component
/// may read another's parameters.
struct InputRateAssumption {
  enum class Kind {
    kSameRate,       // the producer samples at this component's rate (e.g. an observer whose rate is
                     // "the sensor's rate"): slower is an error (one sample passed on as several
                     // new ones), faster a warning (samples between two of its steps are batched)
    kAtLeastMyRate,  // at least one sample per period of this component: slower is a warning
                     // (periods without a new sample)
    kAgeLimit,       // `value_s` judges the input stale: it must be longer than the producer's
                     // period (else stale between any two samples: an error where it applies, a
                     // warning where not) and should be two (else one lost sample: a warning)
  };
  Kind kind = Kind::kSameRate;
  std::string topic;
  std::string key;                    // this component's parameter that states it (rate_hz, input_timeout_s)
  double value_s = 0.0;               // kAgeLimit: the limit, s
  bool realtime_only = false;         // kAgeLimit: the limit applies in real time only
  std::vector<std::uint32_t> robots;  // whose instances it reads; empty: this component's robots
};

class Component {
 public:
  virtual ~Component() = default;
  /// Reads and validates parameters, declares inputs/outputs and the rate. Errors: ConfigError.
  virtual void configure(ComponentContext& ctx) = 0;
  /// Called once when this host starts its run, before the first on_step(): in real time before
  /// the wall clock's first due step, so that one-off work done here (e.g. the evaluator opening
  /// its files) does not make the first steps late. Errors: as on_step().
  virtual void on_start() {}
  /// Called at each due step once the inputs are ready (lockstep) or on the timer (real-time).
  virtual void on_step(const StepInfo& info) = 0;
  /// Called once after the last step (e.g. the evaluator writes its files).
  virtual void on_finish(const StepInfo& /*info*/) {}
  /// Called instead of (or after) on_finish() when the run fails (a RunError in this host: a
  /// timeout, a failed peer, a signal); `reason` is the error line. E.g. the evaluator writes
  /// what it recorded and a summary that says the run failed. Must not block.
  virtual void on_abort(const std::string& /*reason*/) {}
};

/// Wall-clock figures of the run so far, for summary.json's "run" section: the host fills them
/// just before on_finish() (ticks = steps done, wall_time_s = s since this host's run began).
/// `hosts` (summary.json's "hosts" and "inputs"): this host's health first, then, across
/// processes, what the other hosts published on run/health; `hosts_not_heard`: members whose
/// health did not arrive within the wait (docs/architecture.md, "Host health").
struct RunFigures {
  std::uint64_t ticks = 0;
  double wall_time_s = 0.0;
  /// Lockstep: s since this host's run began when its first tick came and when the first and
  /// the second third of the run's steps were done (summary.json run.ticks_per_s_by_third: does
  /// a long run slow down?); fewer than 3 in real time or when the run failed early.
  std::vector<double> thirds_done_at_s;
  std::vector<HostHealth> hosts;
  std::vector<std::string> hosts_not_heard;
  /// Real time: "signal" when a signal stopped the run cleanly before its end (HostOptions::
  /// graceful_stop, stop_at_step); empty: it ran to its end (or failed).
  std::string stopped_by;
  double stopped_at_s = 0.0;            // when stopped: sim time of the last step run (s since step 0)
  std::int64_t stopped_at_wall_ns = 0;  // when stopped: CLOCK_REALTIME as this host's loop ended (ns)
};

/// The scenario's producers of each topic instance: topic -> robot id (0: an unkeyed topic) ->
/// the component names that may publish it (its producer, and a declared hot standby).
using AssignedProducers = std::map<std::string, std::map<std::uint32_t, std::vector<std::string>>>;

/// The instances (instance_key values) a topic is published for, as its producers declare them at
/// configure (ComponentContext::publishes_instances()): topic -> keys in ascending order.
using ProducedInstances = std::map<std::string, std::vector<std::uint64_t>>;

/// What the host knows about the run, shared by all components of a process.
struct RunContext {
  const Scenario* scenario = nullptr;
  Bus* bus = nullptr;
  Notifier* notifier = nullptr;
  TimeMode mode = TimeMode::kLockstep;
  std::string output_dir;   // where the run's recorder writes its files (RunRecording)
  bool single_process = false;  // every component of the run lives in this process (co-located)
  std::string deploy_label;     // how the run is deployed ("colocated", "processes"); empty: a host
                                // started on its own
  std::size_t lockstep_window = 1;  // lockstep: ticks the coordinator may have outstanding (1 = strict)
  RunFigures figures;           // filled by the host before on_finish()
  /// Topics whose readers and writers use DDS exclusive ownership because a hot standby writes
  /// them (exclusive_topics() of runtime/host/producer_check.hpp).
  std::set<std::string> exclusive_topics;
  /// A scenario run: who the scenario lets publish each instance (assigned_producers() of
  /// runtime/host/producer_check.hpp); an input refuses every other writer (unknown_producer).
  /// Null: the first writer of an instance is its producer (a component run without a scenario).
  std::shared_ptr<const AssignedProducers> assigned_producers;
  /// A scenario run: the instances the components declare for the topics they publish
  /// (produced_instances() of runtime/host/producer_check.hpp; topics keyed by two members),
  /// what a recorder of the run waits for. Null outside a scenario run.
  std::shared_ptr<const ProducedInstances> produced_instances;
};

/// What the component that records the run sees of it (ComponentContext::record_run()).
class RunRecording {
 public:
  explicit RunRecording(const RunContext& run) : run_(run) {}
  /// Where to write the run's files (`--out`); empty: write none.
  const std::string& output_dir() const { return run_.output_dir; }
  /// How the run is deployed ("colocated", "processes"); empty: a host started on its own.
  const std::string& deploy_label() const { return run_.deploy_label; }
  /// Lockstep: ticks the coordinator may have outstanding at once (--lockstep-window; 1 = strict).
  std::size_t lockstep_window() const { return run_.lockstep_window; }
  /// The run's figures and every host's health; valid in on_finish() and on_abort().
  const RunFigures& figures() const { return run_.figures; }

 private:
  const RunContext& run_;
};

class ComponentContext {
 public:
  ComponentContext(const RunContext& run, const ComponentSpec& spec, ParamReader params, StepState* state)
      : run_(run), spec_(spec), params_(std::move(params)), state_(state), recording_(run) {}

  const std::string& name() const { return spec_.name; }
  const std::string& type() const { return spec_.type; }
  ParamReader& params() { return params_; }
  const Scenario& scenario() const { return *run_.scenario; }
  /// Robots this component serves, with their initial poses.
  std::vector<RobotSpec> robots() const;
  /// Instance keys of those robots (for Subscription::instances).
  std::vector<std::uint64_t> robot_keys() const;
  /// Seed of the random stream `stream` of this component (scenario seed + name + stream).
  std::uint64_t seed_for(const std::string& stream) const;
  double step_s() const { return run_.scenario->step_s; }
  TimeMode mode() const { return run_.mode; }
  /// Every component of the run lives in this process (co-located).
  bool single_process() const { return run_.single_process; }
  /// Who the scenario lets publish each topic instance (RunContext::assigned_producers): what a
  /// recorder of every published topic subscribes to. Null outside a scenario run, and while
  /// scenario_producers() configures the components to find them.
  const AssignedProducers* assigned_producers() const { return run_.assigned_producers.get(); }
  /// The instances the scenario's components declared for the topics they publish
  /// (RunContext::produced_instances); null outside a scenario run.
  const ProducedInstances* produced_instances() const { return run_.produced_instances.get(); }
  /// Declares, at configure, the instances (instance_key values) this component publishes `topic`
  /// for, when they are not simply its robots: a topic keyed (robot_id, X) whose X the component
  /// chooses (e.g. the other robots it measures). Only the producer knows them before the run; a
  /// recorder of the run (robodds run --record) waits for exactly these at each due step.
  void publishes_instances(const std::string& topic, std::vector<std::uint64_t> keys) {
    std::vector<std::uint64_t>& all = declared_instances_[topic];
    all.insert(all.end(), keys.begin(), keys.end());
  }
  /// What publishes_instances() declared: topic -> keys, in the order declared.
  const ProducedInstances& declared_instances() const { return declared_instances_; }
  /// Makes this component the one that records the run (configure() only; a recorder such as the
  /// evaluator) and gives it what only a recorder needs: where to write, how the run is deployed
  /// and, at its end, the run's figures with every host's health. Across processes its host then
  /// waits, at the end, for the other hosts' run/health reports. The reference stays valid while
  /// the component runs.
  const RunRecording& record_run() {
    records_run_ = true;
    return recording_;
  }
  /// record_run() was called: the host gathers the run's health for this component.
  bool records_run() const { return records_run_; }
  /// This component's wall-clock compute times per stage (summary.json run.timing): e.g.
  /// `ScopedComputeTimer timer(ctx.compute_times(), "cycle");` around the work of a step. Keep
  /// the reference from configure(); the host reports the summaries after the last step.
  ComputeTimes& compute_times() { return compute_times_; }
  const ComputeTimes& compute_times() const { return compute_times_; }

  /// Runs the component every round(1 / (rate_hz * step_s)) steps; the rate must divide the
  /// simulation rate (ConfigError naming `key` otherwise).
  void set_rate_hz(double rate_hz, const std::string& key);
  std::uint64_t period_steps() const { return state_->period_steps; }
  /// The parameter set_rate_hz() was given ("" before it was called: every step, no rate of its own).
  const std::string& rate_key() const { return rate_key_; }

  /// This component assumes `topic` arrives at its own rate (its parameter `key`, e.g. rate_hz:
  /// "the sensor's rate"; kSameRate) or at least at it (kAtLeastMyRate); call set_rate_hz() first.
  /// `robots`: whose instances it reads, if not its own robots (e.g. every team mate's pose).
  void expects_rate_of(const std::string& topic, const std::string& key, InputRateAssumption::Kind kind,
                       std::vector<std::uint32_t> robots = {});
  /// Parameter `key` (`value_s`) judges `topic` stale (kAgeLimit), in real time only when
  /// `realtime_only`; `robots` as above.
  void limits_age_of(const std::string& topic, const std::string& key, double value_s, bool realtime_only,
                     std::vector<std::uint32_t> robots = {});
  /// What expects_rate_of() and limits_age_of() declared, in order.
  const std::vector<InputRateAssumption>& rate_assumptions() const { return rate_assumptions_; }
  /// A freshness limit (parameter `key`, `value_s` s) must be longer than this component's period
  /// (call set_rate_hz() first): an input is only judged stale after at least one of its own due
  /// steps has passed without it. ConfigError naming the key otherwise.
  void require_longer_than_period(const std::string& key, double value_s);

  /// Subscribes to `topic` (ConfigError if it is not in the catalog or carries another type).
  template <class Msg>
  Input<Msg>& subscribe(const std::string& topic, const Subscription& subscription) {
    const TopicInfo& info = checked_topic<Msg>(topic);
    detail::InputOptions options;
    options.expected = subscription.expected();
    options.delay_steps = subscription.delay_steps();
    options.by_robot = subscription.by_robot();
    options.newest_only = subscription.reads_newest_only();
    if (options.by_robot && options.newest_only) {
      throw ConfigError(spec_.name + ": " + topic + ": newest_only() does not combine with robot_streams()");
    }
    if (options.by_robot && info.key.find(',') == std::string::npos) {
      throw ConfigError(spec_.name + ": robot_streams() needs a topic keyed (robot_id, X); " + topic + " is keyed " +
                        (info.key.empty() ? std::string("by nothing") : info.key));
    }
    options.key_names = info.key;
    Bus* bus = run_.bus;
    options.writer_name = [bus](std::uint64_t writer_id) { return bus->writer_name(writer_id); };
    options.exclusive_ownership = run_.exclusive_topics.count(topic) != 0;
    options.send_once = info.qos_class == QosClass::kMission;
    options.producer_assigned = assigned_producer_rule(topic);
    for (const RobotSpec& robot : run_.scenario->robots) {
      options.known_robots.push_back(robot.id);
    }
    auto input = std::make_unique<Input<Msg>>(topic, spec_.name, state_, run_.notifier, std::move(options));
    Input<Msg>* raw = input.get();
    SampleCallback on_sample = [raw](const void* sample, const SampleMeta& meta) {
      raw->on_sample(*static_cast<const Msg*>(sample), meta);
    };
    ReaderEventCallback on_event = reader_events(topic);
    const std::string profile = qos_profile_for(info, run_.mode, run_.single_process);
    if (raw->filters_keys()) {
      // Keys of robots outside the scenario are dropped by the transport before it keeps any
      // state for them, and still counted here as unknown_key (issue 24, finding 4).
      KeyFilter filter{[raw](std::uint64_t key) { return raw->takes_key(key); },
                       [raw](std::uint64_t key, std::uint64_t writer_id) { raw->count_unknown_key(key, writer_id); }};
      readers_.push_back(run_.bus->filtered_reader(topic, info.type_name, profile, std::move(on_sample), std::move(on_event),
                                                   std::move(filter)));
    } else {
      readers_.push_back(run_.bus->reader(topic, info.type_name, profile, std::move(on_sample), std::move(on_event)));
    }
    raw->attach_reader(readers_.back().get());
    inputs_.push_back(std::move(input));
    return *raw;
  }

  /// A run whose components all live in this process (co-located): `on_sample` gets every sample
  /// of `topic` they write, inside the writer's write(), in write order, with no checks (see
  /// delivery_check()), no producer rule and no lockstep wait. For a recorder of such a run: an
  /// Input's queue, gate and bookkeeping cost it about as much CPU on the step as the recording
  /// itself (docs/performance.md, "Recording in the run"). ConfigError in any other run, where
  /// samples come from other processes on DDS threads and only an Input orders them.
  template <class Msg>
  void observe_local(const std::string& topic, std::function<void(const Msg&, const SampleMeta&)> on_sample) {
    const TopicInfo& info = checked_topic<Msg>(topic);
    if (!run_.single_process) {
      throw ConfigError(spec_.name + ": observe_local(" + topic + ") needs every component in this process");
    }
    SampleCallback callback = [on_sample = std::move(on_sample)](const void* sample, const SampleMeta& meta) {
      on_sample(*static_cast<const Msg*>(sample), meta);
    };
    readers_.push_back(run_.bus->reader(topic, info.type_name, qos_profile_for(info, run_.mode, run_.single_process),
                                        std::move(callback), reader_events(topic)));
  }

  template <class Msg>
  Output<Msg>& advertise(const std::string& topic) {
    const TopicInfo& info = checked_topic<Msg>(topic);
    // A mission's last sample stays for readers that join later; a stream's ended instances go.
    const InstanceEnds ends = info.qos_class == QosClass::kMission ? InstanceEnds::kKept : InstanceEnds::kForgotten;
    auto output = std::make_unique<Output<Msg>>(
        run_.bus->writer(topic, info.type_name, qos_profile_for(info, run_.mode, run_.single_process)), state_, ends);
    Output<Msg>* raw = output.get();
    outputs_.push_back(std::shared_ptr<void>(output.release(), [](void* p) { delete static_cast<Output<Msg>*>(p); }));
    return *raw;
  }

  const std::vector<std::unique_ptr<InputBase>>& inputs() const { return inputs_; }

 private:
  /// What a reader of `topic` reports (an incompatible QoS, a lost sample): a warning by this component.
  ReaderEventCallback reader_events(const std::string& topic) const {
    return [owner = spec_.name, topic](const std::string& event) { log::warn(owner, topic + ": " + event); };
  }

  /// InputOptions::producer_assigned of `topic` in a scenario run: a writer may publish a robot's
  /// instances if its process runs a component the scenario assigns to them, or if the scenario
  /// assigns them none; empty (the first writer rule) without RunContext::assigned_producers or
  /// when no component of the scenario publishes the topic.
  std::function<bool(std::uint64_t, std::uint32_t)> assigned_producer_rule(const std::string& topic) const;

  template <class Msg>
  const TopicInfo& checked_topic(const std::string& topic) const {
    const TopicInfo& info = topic_info(topic);
    if (info.type_name != idl::type_name<Msg>()) {
      throw ConfigError(spec_.name + ": topic " + topic + " carries " + info.type_name + ", not " + idl::type_name<Msg>());
    }
    return info;
  }

  const RunContext& run_;
  const ComponentSpec& spec_;
  ParamReader params_;
  StepState* state_;
  std::vector<std::unique_ptr<InputBase>> inputs_;
  std::vector<std::shared_ptr<void>> outputs_;
  std::vector<std::shared_ptr<ReaderHandle>> readers_;
  bool records_run_ = false;
  std::string rate_key_;
  std::vector<InputRateAssumption> rate_assumptions_;
  ProducedInstances declared_instances_;
  RunRecording recording_;
  ComputeTimes compute_times_;
};

}  // namespace robodds
