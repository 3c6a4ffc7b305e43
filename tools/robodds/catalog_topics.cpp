#include "tools/robodds/catalog_topics.hpp"

#include <set>

#include "common/did_you_mean.hpp"
#include "runtime/topics/topic_names.hpp"
#include "runtime/base/error.hpp"

namespace robodds {

std::vector<const TopicInfo*> catalog_topics(const std::vector<std::string>& names, const std::string& option) {
  std::vector<const TopicInfo*> chosen;
  if (names.empty()) {
    for (const TopicInfo& topic : topic_catalog()) {
      chosen.push_back(&topic);
    }
    return chosen;
  }
  std::set<std::string> seen;
  for (const std::string& name : names) {
    const TopicInfo* topic = find_topic(name);
    if (topic == nullptr) {
      throw ConfigError((option.empty() ? "" : option + ": ") + "unknown topic '" + name + "'" + did_you_mean(name, topic_names()) +
                        " (`robodds record --list` lists the topics it can record)");
    }
    if (seen.insert(name).second) {
      chosen.push_back(topic);
    }
  }
  return chosen;
}

}  // namespace robodds
