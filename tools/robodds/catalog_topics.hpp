#pragma once
// The topics a tool (`robodds record`, `robodds bridge`) is asked for, by name, from the catalog.
#include <string>
#include <vector>

#include "runtime/topics/topic_catalog.hpp"

namespace robodds {

/// The catalog's topics named in `names`, in the order given, each once; empty `names`: every
/// topic of the catalog. A name the catalog does not have is a ConfigError naming it, after
/// `option` (e.g. "--topics"; empty for positional names).
std::vector<const TopicInfo*> catalog_topics(const std::vector<std::string>& names, const std::string& option);

}  // namespace robodds
