#pragma once
// The names of the catalog's topics, for did_you_mean() when a name is not one of them.

#include <string>
#include <vector>

#include "runtime/topics/topic_catalog.hpp"

namespace robodds {

/// The name of every topic of the catalog, in its order.
inline std::vector<std::string> topic_names() {
  std::vector<std::string> names;
  for (const TopicInfo& topic : topic_catalog()) {
    names.push_back(topic.name);
  }
  return names;
}

}  // namespace robodds
