#include "sim/replay_source/replay_chain.hpp"

#include <algorithm>
#include <limits>
#include <map>
#include <unordered_map>

namespace robodds::replay_source {

std::string chain_problem(const std::vector<ChainLink>& links, std::uint64_t last_step) {
  std::uint64_t recorded_until = 0;
  for (const ChainLink& l : links) recorded_until = std::max(recorded_until, l.step);
  // Sorted by stream name, then step, equal ones in their given order: a stable sort of indices by
  // the stream's rank among the names (a recording holds few streams and many samples: integers
  // are compared and moved, not names and links).
  std::unordered_map<std::string, std::uint32_t> rank;
  for (const ChainLink& l : links) rank.emplace(l.stream, 0);
  std::vector<const std::string*> names;
  names.reserve(rank.size());
  for (const auto& [name, r] : rank) names.push_back(&name);
  std::sort(names.begin(), names.end(), [](const std::string* a, const std::string* b) { return *a < *b; });
  for (std::size_t i = 0; i < names.size(); ++i) rank[*names[i]] = static_cast<std::uint32_t>(i);
  struct Key {
    std::uint32_t stream;
    std::uint64_t step;
    std::size_t index;
  };
  std::vector<Key> order;
  order.reserve(links.size());
  for (std::size_t i = 0; i < links.size(); ++i) order.push_back({rank.at(links[i].stream), links[i].step, i});
  std::stable_sort(order.begin(), order.end(), [](const Key& a, const Key& b) {
    return a.stream != b.stream ? a.stream < b.stream : a.step < b.step;
  });
  constexpr std::uint64_t kNever = std::numeric_limits<std::uint64_t>::max();
  for (std::size_t i = 0; i < order.size(); ++i) {
    const ChainLink& l = links[order[i].index];
    const bool last_of_stream = i + 1 == order.size() || order[i + 1].stream != order[i].stream;
    if (!last_of_stream) {
      const ChainLink& next = links[order[i + 1].index];
      if (next.step == l.step) {
        return l.stream + ": two samples of step " + std::to_string(l.step) + " (two runs in one file?)";
      }
      if (next.step != l.next_step) {
        return l.stream + ": the sample of step " + std::to_string(l.step) + " announces step " +
               std::to_string(l.next_step) + " but the next one recorded is of step " + std::to_string(next.step) +
               " (samples were lost while recording)";
      }
    } else if (l.next_step != kNever && l.next_step > recorded_until && l.next_step <= last_step) {
      return l.stream + ": the recording ends at step " + std::to_string(recorded_until) + " but the run goes to step " +
             std::to_string(last_step) + " (shorten the run with --duration or record longer)";
    }
  }
  return {};
}

std::vector<std::string> late_topics(const std::vector<ChainLink>& links) {
  std::map<std::string, std::uint64_t> first;  // topic -> its earliest step
  for (const ChainLink& l : links) {
    const auto it = first.find(l.topic);
    if (it == first.end() || l.step < it->second) first[l.topic] = l.step;
  }
  std::vector<std::string> out;
  for (const auto& [topic, step] : first) {
    if (step > 0) out.push_back(topic + ": its first recorded sample is of step " + std::to_string(step));
  }
  return out;
}

std::map<std::string, std::vector<std::uint64_t>> instances_of(const std::vector<ChainLink>& links,
                                                              const std::set<std::string>& topics) {
  std::map<std::string, std::set<std::uint64_t>> found;
  for (const ChainLink& l : links) {
    if (topics.count(l.topic) != 0) found[l.topic].insert(l.key);
  }
  std::map<std::string, std::vector<std::uint64_t>> out;
  for (const auto& [topic, keys] : found) out[topic].assign(keys.begin(), keys.end());  // std::set: ascending
  return out;
}

namespace {

std::string robot_list(const std::vector<std::uint32_t>& robots) {
  std::string out;
  for (const std::uint32_t r : robots) out += (out.empty() ? "" : ", ") + std::to_string(r);
  return out.empty() ? "none" : out;
}

bool has(const std::vector<std::uint32_t>& robots, std::uint32_t robot) {
  return std::find(robots.begin(), robots.end(), robot) != robots.end();
}

}  // namespace

std::string foreign_pair(const std::vector<ChainLink>& links, const std::set<std::string>& topics,
                         const std::vector<std::uint32_t>& served, const std::vector<std::uint32_t>& robots) {
  for (const ChainLink& l : links) {
    if (topics.count(l.topic) == 0) continue;
    const auto robot = static_cast<std::uint32_t>(l.key >> 32);
    const auto peer = static_cast<std::uint32_t>(l.key & 0xffffffffULL);
    if (!has(robots, robot) || !has(robots, peer)) {
      return l.stream + ": robot " + std::to_string(has(robots, robot) ? peer : robot) +
             " is not a robot of the scenario (its robots: " + robot_list(robots) + ")";
    }
    if (!has(served, robot)) {
      return l.stream + ": robot " + std::to_string(robot) + " is not one of the replay's robots (" + robot_list(served) + ")";
    }
  }
  return {};
}

}  // namespace robodds::replay_source
