#include "runtime/io/input_base.hpp"

#include <algorithm>

#include "runtime/base/log.hpp"

namespace robodds {

void InputBase::note_lost_samples(const Progress& p, const std::string& label, std::uint64_t step) {
  lockstep_error_ = "lockstep: topic " + topic_ + " (" + label + ") lost samples: after step " + std::to_string(p.step) +
                    ", whose sample announced the next at step " + std::to_string(p.next_step) + ", came step " +
                    std::to_string(step) + " (a sample dropped and no longer in the writer's history, or one that "
                    "could not be decoded: see summary.json hosts.*.undecodable)";
  log::error(owner_, lockstep_error_);
}

bool InputBase::accept_other_writer(Progress& p, const std::string& label, const SampleMeta& meta, bool sample_ok) {
  const std::string old_writer = writer_label(p.producer);
  const std::string new_writer = writer_label(meta.writer_id);
  // Silence is judged on the producer's accepted samples; a send-once topic's producer is never
  // silent, and a sample that fails its checks takes nothing over.
  const bool silent = !options_.send_once && sample_ok && meta.received_ns != 0 && p.received_ns != 0 &&
                      meta.received_ns - p.received_ns > detail::kProducerSilenceNs;
  if (options_.exclusive_ownership || (state_->mode == TimeMode::kRealtime && silent)) {
    log::warn(owner_, topic_ + " (" + label + "): hand-over from " + old_writer + " to " + new_writer +
                      (options_.exclusive_ownership ? " (exclusive ownership)" : " (the old producer fell silent)"));
    p.producer = meta.writer_id;
    return true;
  }
  if (state_->mode == TimeMode::kLockstep) {
    if (lockstep_error_.empty()) {
      lockstep_error_ = "lockstep: topic " + topic_ + " (" + label + ") has two producers: " + old_writer + " and " +
                        new_writer + " (a second component or a restarted process publishes this instance; one "
                        "producer per topic instance)";
      log::error(owner_, lockstep_error_);
    }
    ++counts_.rejected[detail::kRejectSecondProducer];
    return false;
  }
  count_rejection(detail::kRejectSecondProducer,
                  "(" + label + "): this instance's producer is " + old_writer + "; first writer wins", meta.writer_id);
  return false;
}

std::string InputBase::writer_label(std::uint64_t writer_id) const {
  if (writer_id == 0) {
    return "an unnamed writer";  // SampleMeta 0: e.g. a sample the transport's key filter dropped
  }
  return options_.writer_name ? options_.writer_name(writer_id) : "writer " + std::to_string(writer_id);
}

void InputBase::log_rejection(const std::string& detail, std::uint64_t writer_id) const {
  log::warn(owner_, "rejected a sample on " + topic_ + " from " + writer_label(writer_id) + " " + detail +
                      "; such samples are counted and dropped (logged once per writer and reason)");
}

std::string InputBase::label_of(std::uint64_t key) const {
  if (options_.by_robot) {
    const std::size_t s = stream_index_.find(key);
    if (s != KeyIndex::kNone && streams_[s].has_current) {
      key = streams_[s].current_key;
    }
  }
  const std::size_t i = instance_index_.find(key);
  if (i != KeyIndex::kNone) {
    return instances_[i].label;
  }
  auto preset = options_.labels.find(key);
  if (preset != options_.labels.end()) {
    return preset->second;
  }
  // Not seen yet: spell the key with the topic's key field names ("robot_id, target_id").
  const std::string& names = options_.key_names;
  if (options_.by_robot) {
    const std::size_t comma = names.find(',');
    return names.substr(0, comma) + "=" + std::to_string(key) + " (any " + names.substr(comma + 2) + ")";
  }
  return instance_key_text(names, key);
}

std::string instance_key_text(const std::string& names, std::uint64_t key) {
  const std::size_t comma = names.find(',');
  if (names.empty()) {
    return "instance " + std::to_string(key);
  }
  if (comma == std::string::npos) {
    return names + "=" + std::to_string(key);
  }
  std::string second = names.substr(comma + 1);
  second.erase(0, second.find_first_not_of(' '));
  return names.substr(0, comma) + "=" + std::to_string(key >> 32) + " " + second + "=" + std::to_string(key & 0xffffffffULL);
}

std::size_t InputBase::add_instance(std::uint64_t key, std::size_t stream, std::string label) {
  const std::size_t i = instance_index_.insert(key).first;
  auto preset = options_.labels.find(key);
  instances_.push_back(Instance{key, preset != options_.labels.end() ? preset->second : std::move(label), stream});
  // The robot's instances in key order (the *_of_robot() reads go through them in that order).
  const auto [r, added] = robot_index_.insert(key >> 32);
  if (added) {
    robot_instances_.emplace_back();
  }
  std::vector<std::size_t>& of_robot = robot_instances_[r];
  of_robot.insert(std::upper_bound(of_robot.begin(), of_robot.end(), key,
                                   [this](std::uint64_t k, std::size_t n) { return k < instances_[n].key; }),
                  i);
  return i;
}

}  // namespace robodds
