#include "runtime/dds/key_filter.hpp"

#include <utility>

namespace robodds {
namespace dds = eprosima::fastdds::dds;
using eprosima::fastrtps::types::ReturnCode_t;

ReaderKeyFilter::ReaderKeyFilter(dds::TypeSupport type, const std::string& type_name)
    : type_(std::move(type)), key_(sample_key_function(type_name)) {
  sample_ = type_->createData();
}

ReaderKeyFilter::~ReaderKeyFilter() { type_->deleteData(sample_); }

void ReaderKeyFilter::add(KeyFilter filter) {
  std::lock_guard<std::mutex> lock(mutex_);
  rules_.push_back(std::move(filter));
}

void ReaderKeyFilter::add_unfiltered() {
  std::lock_guard<std::mutex> lock(mutex_);
  ++unfiltered_;
}

bool ReaderKeyFilter::filters() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return unfiltered_ == 0 && !rules_.empty() && key_ != nullptr;
}

bool ReaderKeyFilter::evaluate(const SerializedPayload& payload, const FilterSampleInfo& /*sample_info*/,
                               const GUID_t& /*reader_guid*/) const {
  std::lock_guard<std::mutex> lock(mutex_);
  if (unfiltered_ > 0 || rules_.empty() || key_ == nullptr) {
    return true;
  }
  // The type support's deserialize() takes a non-const payload (it records the encapsulation):
  // decode a copy, reused from sample to sample (no allocation once it has the largest size).
  scratch_.copy(&payload, false);
  if (!type_->deserialize(&scratch_, sample_)) {
    dropped_.fetch_add(1, std::memory_order_relaxed);
    return false;  // counted as undecodable by the type support (GuardedType), as a take would
  }
  const std::uint64_t key = key_(sample_);
  for (const KeyFilter& rule : rules_) {
    if (rule.takes && rule.takes(key)) {
      return true;
    }
  }
  dropped_.fetch_add(1, std::memory_order_relaxed);
  // Writer 0 (unknown): Fast DDS does not tell a filter the sample's writer (its FilterSampleInfo
  // holds only a sample identity the writer may send in the inline QoS, and ours do not).
  for (const KeyFilter& rule : rules_) {
    if (rule.refused) {
      rule.refused(key, 0);
    }
  }
  return false;
}

void KeyFilterFactory::add(const std::string& expression, ReaderKeyFilter* filter) {
  std::lock_guard<std::mutex> lock(mutex_);
  filters_[expression] = filter;
}

ReturnCode_t KeyFilterFactory::create_content_filter(const char* filter_class_name, const char* /*type_name*/,
                                                     const dds::TopicDataType* /*data_type*/, const char* filter_expression,
                                                     const ParameterSeq& /*filter_parameters*/,
                                                     dds::IContentFilter*& filter_instance) {
  if (filter_class_name == nullptr || class_name_ != filter_class_name) {
    return ReturnCode_t::RETCODE_BAD_PARAMETER;
  }
  if (filter_expression == nullptr) {
    // Only the parameters change (ContentFilteredTopic::set_expression_parameters): ours have none.
    return filter_instance != nullptr ? ReturnCode_t::RETCODE_OK : ReturnCode_t::RETCODE_BAD_PARAMETER;
  }
  std::lock_guard<std::mutex> lock(mutex_);
  auto it = filters_.find(filter_expression);
  if (it == filters_.end()) {
    return ReturnCode_t::RETCODE_BAD_PARAMETER;
  }
  filter_instance = it->second;
  return ReturnCode_t::RETCODE_OK;
}

ReturnCode_t KeyFilterFactory::delete_content_filter(const char* /*filter_class_name*/,
                                                     dds::IContentFilter* /*filter_instance*/) {
  return ReturnCode_t::RETCODE_OK;  // the bus owns its filters
}

}  // namespace robodds
