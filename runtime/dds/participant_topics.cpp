#include "runtime/dds/participant_topics.hpp"

#include <fastdds/dds/topic/TypeSupport.hpp>
#include <fastdds/dds/topic/qos/TopicQos.hpp>

#include "runtime/base/error.hpp"

namespace robodds {

namespace dds = eprosima::fastdds::dds;
using eprosima::fastrtps::types::ReturnCode_t;

dds::Topic* ParticipantTopics::ensure(dds::DomainParticipant& participant, const std::string& topic,
                                      const std::string& type_name, const TypeFactory& make_type) {
  auto it = topics_.find(topic);
  if (it != topics_.end()) {
    if (it->second->get_type_name() != type_name) {
      throw ConfigError("topic " + topic + " is used with two types: " + it->second->get_type_name() + " and " + type_name);
    }
    return it->second;
  }
  if (registered_types_.count(type_name) == 0) {
    dds::TopicDataType* type = make_type(type_name);
    if (type == nullptr) {
      throw ConfigError("topic " + topic + ": unknown type " + type_name);
    }
    dds::TypeSupport support(type);
    if (support.register_type(&participant) != ReturnCode_t::RETCODE_OK) {
      throw RunError("could not register type " + type_name);
    }
    registered_types_.insert(type_name);
  }
  dds::Topic* created = participant.create_topic(topic, type_name, dds::TOPIC_QOS_DEFAULT);
  if (created == nullptr) {
    throw RunError("could not create topic " + topic);
  }
  topics_[topic] = created;
  return created;
}

}  // namespace robodds
