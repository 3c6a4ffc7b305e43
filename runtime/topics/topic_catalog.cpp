#include "runtime/topics/topic_catalog.hpp"

#include "common/did_you_mean.hpp"
#include "runtime/base/error.hpp"
#include "runtime/topics/topic_names.hpp"

namespace robodds {

namespace {

std::vector<TopicInfo>& catalog() {
  static std::vector<TopicInfo> topics = {
      make_topic<idl::SimTick>("sim/clock", QosClass::kLockstep, "coordinator (`robodds run`)", "every host"),
      make_topic<idl::StepDone>("sim/step_done", QosClass::kLockstep, "every host", "coordinator"),
      make_topic<idl::HostReport>("run/health", QosClass::kMission, "every host across processes (once, at its end)",
                                  "the host of a component that asked for the run's health (summary.json `hosts`, `inputs`, `run.timing`)"),
      make_topic<idl::HostAlive>("run/alive", QosClass::kState,
                                 "every real-time host across processes (every 0.2 s, from its loop)",
                                 "every other real-time host of the run (a silent loop is a lost host)"),
  };
  return topics;
}

/// What the runtime relies on agrees (the producers and consumers are documentation).
bool same(const TopicInfo& a, const TopicInfo& b) {
  return a.type_name == b.type_name && a.qos_class == b.qos_class && a.key == b.key;
}

}  // namespace

const std::vector<TopicInfo>& topic_catalog() { return catalog(); }

void add_topics(const std::vector<TopicInfo>& topics) {
  for (const TopicInfo& topic : topics) {
    if (const TopicInfo* known = find_topic(topic.name)) {
      if (!same(*known, topic)) {
        throw ConfigError("topic catalog: topic '" + topic.name + "' is added twice with different types, QoS or keys (" +
                          known->type_name + " and " + topic.type_name + ")");
      }
      continue;
    }
    catalog().push_back(topic);
  }
}

const TopicInfo* find_topic(const std::string& name) {
  for (const TopicInfo& topic : topic_catalog()) {
    if (topic.name == name) {
      return &topic;
    }
  }
  return nullptr;
}

const TopicInfo& topic_info(const std::string& name) {
  if (const TopicInfo* topic = find_topic(name)) {
    return *topic;
  }
  std::string known;
  for (const TopicInfo& topic : topic_catalog()) {
    known += (known.empty() ? "" : ", ") + topic.name;
  }
  throw ConfigError("unknown topic '" + name + "'" + did_you_mean(name, topic_names()) + " (known: " + known + ")");
}

std::string qos_profile_for(const TopicInfo& topic, TimeMode mode, bool single_process) {
  if (mode == TimeMode::kLockstep && topic.qos_class != QosClass::kMission) {
    return single_process ? kLockstepLocalProfile : kLockstepProfile;
  }
  return to_string(topic.qos_class);
}

std::string monitor_profile_for(const TopicInfo& topic) {
  return topic.qos_class == QosClass::kMission ? kMissionProfile : kMonitorProfile;
}

}  // namespace robodds
