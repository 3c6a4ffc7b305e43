#include "runtime/dds/type_support.hpp"

#include <fastcdr/exceptions/Exception.h>

#include <map>
#include <mutex>

#include "robodds/idl/roboddsPubSubTypes.h"
#include "robodds/idl/robodds_visit.hpp"
#include "runtime/dds/undecodable.hpp"
#include "runtime/base/log.hpp"
#include "runtime/topics/topic_catalog.hpp"

namespace robodds {
namespace {

/// Undecodable samples per type name in this process.
class UndecodableCounts {
 public:
  /// Counts one; true the first time for this type (log it then).
  bool add(const std::string& type_name) {
    std::lock_guard<std::mutex> lock(mutex_);
    return ++counts_[type_name] == 1;
  }
  std::uint64_t get(const std::string& type_name) const {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = counts_.find(type_name);
    return it == counts_.end() ? 0 : it->second;
  }

 private:
  mutable std::mutex mutex_;
  std::map<std::string, std::uint64_t> counts_;
};

UndecodableCounts& undecodable_counts() {
  static UndecodableCounts counts;
  return counts;
}

/// The catalog topics of a type, for the log line (a type may serve several topics: all are
/// named).
std::string topics_of(const std::string& type_name) {
  std::string names;
  for (const TopicInfo& topic : topic_catalog()) {
    if (topic.type_name == type_name) {
      names += (names.empty() ? "" : ", ") + topic.name;
    }
  }
  return names.empty() ? "(no catalog topic)" : names;
}

void note_undecodable(const std::string& type_name, const std::string& reason) {
  if (undecodable_counts().add(type_name)) {
    log::warn("dds", "dropped an undecodable sample on " + topics_of(type_name) + " (type " + type_name + ": " + reason +
                         "); such samples are counted and dropped (logged once per type)");
  }
}

/// The generated type support, except that a payload it cannot decode is dropped and counted
/// instead of thrown. fastddsgen 2.3's deserialize() catches only NotEnoughMemoryException;
/// Fast CDR throws BadParamException for a bad encapsulation header or a boolean byte other
/// than 0/1, and Fast DDS 2.9 calls deserialize() inside DataReader::take_next_sample() (and,
/// for a sample without a key hash, in its receive thread) without catching: one such payload
/// from any writer on the domain aborted the process (std::terminate). docs/interop.md.
template <class Generated>
class GuardedType : public Generated {
 public:
  explicit GuardedType(bool count_undecodable) : count_(count_undecodable) {}
  bool deserialize(eprosima::fastrtps::rtps::SerializedPayload_t* payload, void* data) override {
    try {
      if (Generated::deserialize(payload, data)) {
        return true;
      }
      note("payload shorter than the type");
    } catch (const eprosima::fastcdr::exception::Exception& e) {
      note(std::string("Fast CDR: ") + e.what());
    }
    return false;
  }

 private:
  void note(const std::string& reason) {
    if (count_) {
      note_undecodable(Generated::getName(), reason);
    }
  }
  bool count_;
};

}  // namespace

eprosima::fastdds::dds::TopicDataType* make_type_support(const std::string& type_name, bool count_undecodable) {
  eprosima::fastdds::dds::TopicDataType* type = nullptr;
#define ROBODDS_MAKE_TYPE(T)                          \
  if (type == nullptr && type_name == idl::type_name<idl::T>()) { \
    type = new GuardedType<idl::T##PubSubType>(count_undecodable); \
  }
  ROBODDS_FOR_EACH_TOPIC_TYPE(ROBODDS_MAKE_TYPE)
#undef ROBODDS_MAKE_TYPE
  if (type != nullptr) {
    type->auto_fill_type_object(false);
    type->auto_fill_type_information(false);
  }
  return type;
}

std::uint64_t undecodable_samples(const std::string& type_name) { return undecodable_counts().get(type_name); }

}  // namespace robodds
