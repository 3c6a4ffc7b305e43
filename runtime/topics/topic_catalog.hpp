#pragma once
// The topics of the run: name, IDL type, QoS class, key, producers and consumers. The single
// source for the runtime (type checks, QoS profile choice), the topic CLI and docs/topics.md.
// The runtime's own topics (the lockstep bookkeeping: sim/clock, sim/step_done, run/health) are
// always there; the system built on the runtime adds its topics with add_topics() before any
// run starts (system/topics.hpp), so the runtime names none of them.

#include <string>
#include <utility>
#include <vector>

#include "robodds/idl/robodds_visit.hpp"
#include "runtime/bus/bus.hpp"
#include "runtime/bus/qos_profiles.hpp"

namespace robodds {

struct TopicInfo {
  std::string name;
  std::string type_name;  // e.g. robodds::idl::SimTick
  QosClass qos_class;     // the real-time profile; lockstep substitutes (qos_profile_for)
  std::string key;        // key members in IDL order, e.g. "robot_id, peer_id"; "-" = unkeyed (from the IDL)
  std::string producers;  // free text (markdown), shown only in docs/topics.md
  std::string consumers;  // free text (markdown), shown only in docs/topics.md
};

/// One catalog entry of IDL type Msg: its type name and key come from the IDL (the generated
/// idl::type_name<Msg>() and idl::key_names<Msg>()), so they cannot disagree with it.
template <class Msg>
TopicInfo make_topic(std::string name, QosClass qos_class, std::string producers, std::string consumers) {
  return TopicInfo{std::move(name), idl::type_name<Msg>(), qos_class, idl::key_names<Msg>(), std::move(producers),
                   std::move(consumers)};
}

/// Every topic: the runtime's own first, then those added, in the order added.
const std::vector<TopicInfo>& topic_catalog();
/// Adds topics to the catalog; call before any run starts (the catalog is read without a lock).
/// A topic already there with the same info is skipped (adding twice is harmless); one of the
/// same name with other info throws ConfigError naming the topic.
void add_topics(const std::vector<TopicInfo>& topics);
/// nullptr if the topic is not in the catalog.
const TopicInfo* find_topic(const std::string& name);
/// The topic's info; throws ConfigError naming the topic and the known topics.
const TopicInfo& topic_info(const std::string& name);

/// QoS profile used for a topic in a time mode. Simulated time (lockstep) must lose nothing and
/// must not depend on discovery timing, so every data topic uses the reliable, transient-local
/// `lockstep` profile there (missions keep `mission`); real-time uses the topic's own class.
/// `single_process`: every component of the run is in this process (co-located run), so lockstep
/// topics use `lockstep_local` (intra-process delivery is lossless without the reliable protocol).
std::string qos_profile_for(const TopicInfo& topic, TimeMode mode, bool single_process);

/// QoS profile of a passive reader of the topic (`robodds echo`): `monitor`, which matches
/// writers of every profile, except `mission` for missions so a late reader still gets the
/// last mission (transient local).
std::string monitor_profile_for(const TopicInfo& topic);

}  // namespace robodds
