#include "runtime/dds/type_support.hpp"

#include "robodds/idl/roboddsPubSubTypes.h"
#include "robodds/idl/robodds_visit.hpp"

namespace robodds {

eprosima::fastdds::dds::TopicDataType* make_type_support(const std::string& type_name) {
  eprosima::fastdds::dds::TopicDataType* type = nullptr;
#define ROBODDS_MAKE_TYPE(T)                          \
  if (type == nullptr && type_name == idl::type_name<idl::T>()) { \
    type = new idl::T##PubSubType();                  \
  }
  ROBODDS_FOR_EACH_TOPIC_TYPE(ROBODDS_MAKE_TYPE)
#undef ROBODDS_MAKE_TYPE
  if (type != nullptr) {
    type->auto_fill_type_object(false);
    type->auto_fill_type_information(false);
  }
  return type;
}

}  // namespace robodds
