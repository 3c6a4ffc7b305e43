#pragma once
// The topics one DomainParticipant created, by name, each type registered once (runtime-internal;
// includes Fast DDS). The typed bus (dds_bus) and the raw one (raw_bus) share it.

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/topic/Topic.hpp>
#include <fastdds/dds/topic/TopicDataType.hpp>

#include <functional>
#include <map>
#include <set>
#include <string>

namespace robodds {

class ParticipantTopics {
 public:
  /// The type support to register for a type name; null: a type we do not know.
  using TypeFactory = std::function<eprosima::fastdds::dds::TopicDataType*(const std::string& type_name)>;

  /// `topic` of `type_name` on `participant`: the one created before, or created now (its type
  /// registered first, once per type, from `make_type`). ConfigError when the topic exists with
  /// another type or `make_type` knows no such type; RunError when Fast DDS refuses.
  eprosima::fastdds::dds::Topic* ensure(eprosima::fastdds::dds::DomainParticipant& participant, const std::string& topic,
                                        const std::string& type_name, const TypeFactory& make_type);
  /// A topic ensure() created; std::out_of_range otherwise.
  eprosima::fastdds::dds::Topic* at(const std::string& topic) const { return topics_.at(topic); }

 private:
  std::set<std::string> registered_types_;
  std::map<std::string, eprosima::fastdds::dds::Topic*> topics_;  // owned by the participant
};

}  // namespace robodds
