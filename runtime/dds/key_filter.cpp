#include "runtime/dds/key_filter.hpp"

#include <memory>
#include <optional>
#include <string>
#include <utility>

namespace robodds {
namespace dds = eprosima::fastdds::dds;
using eprosima::fastrtps::types::ReturnCode_t;

namespace {
struct WritingNow {
  const void* sample = nullptr;
  SampleStepsFunction steps_of_type = nullptr;
};
thread_local WritingNow writing_now;
}  // namespace

SampleBeingWritten::SampleBeingWritten(const void* sample, SampleStepsFunction steps_of_type)
    : outer_sample_(writing_now.sample), outer_steps_of_type_(writing_now.steps_of_type) {
  writing_now = WritingNow{sample, steps_of_type};
}

SampleBeingWritten::~SampleBeingWritten() { writing_now = WritingNow{outer_sample_, outer_steps_of_type_}; }

const void* SampleBeingWritten::of_type(SampleStepsFunction steps_of_type) {
  const WritingNow& now = writing_now;
  return now.sample != nullptr && steps_of_type != nullptr && now.steps_of_type == steps_of_type ? now.sample : nullptr;
}

ReaderKeyFilter::ReaderKeyFilter(dds::TypeSupport type, const std::string& type_name, Side side)
    : type_(std::move(type)), key_(sample_key_function(type_name)), steps_(sample_steps_function(type_name)), side_(side) {
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

void ReaderKeyFilter::read_only(const StepNeeds& needs) {
  std::lock_guard<std::mutex> lock(mutex_);
  needs_ = needs;
}

bool ReaderKeyFilter::evaluate(const SerializedPayload& payload, const FilterSampleInfo& /*sample_info*/,
                               const GUID_t& /*reader_guid*/) const {
  std::lock_guard<std::mutex> lock(mutex_);
  const bool check_keys = unfiltered_ == 0 && !rules_.empty() && key_ != nullptr;
  const bool check_steps = needs_ && !needs_->all() && steps_ != nullptr;
  if (!check_keys && !check_steps) {
    return true;
  }
  if (side_ == Side::kWriter && !check_keys) {
    if (const void* sample = SampleBeingWritten::of_type(steps_)) {
      return passes_steps(sample);  // the sample this payload was encoded from (no decode)
    }
  }
  // The type support's deserialize() takes a non-const payload (it records the encapsulation):
  // decode a copy, reused from sample to sample (no allocation once it has the largest size).
  scratch_.copy(&payload, false);
  if (!type_->deserialize(&scratch_, sample_)) {
    if (side_ == Side::kWriter) {
      return true;  // e.g. an instance's end (key only): the reader judges it
    }
    dropped_.fetch_add(1, std::memory_order_relaxed);
    return false;  // counted as undecodable by the type support (GuardedType), as a take would
  }
  if (check_keys && !takes_key()) {
    return false;
  }
  return !check_steps || passes_steps(sample_);
}

bool ReaderKeyFilter::passes_steps(const void* sample) const {
  const SampleSteps steps = steps_(sample);
  if (!needs_->needs(steps.step, steps.next_step)) {
    left_out_.fetch_add(1, std::memory_order_relaxed);
    return false;
  }
  return true;
}

bool ReaderKeyFilter::takes_key() const {
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

ReturnCode_t KeyFilterFactory::create_content_filter(const char* filter_class_name, const char* type_name,
                                                     const dds::TopicDataType* /*data_type*/, const char* filter_expression,
                                                     const ParameterSeq& /*filter_parameters*/,
                                                     dds::IContentFilter*& filter_instance) {
  const bool steps_class = filter_class_name != nullptr && std::string(filter_class_name) == kStepClass;
  if (filter_class_name == nullptr || (class_name_ != filter_class_name && !steps_class)) {
    return ReturnCode_t::RETCODE_BAD_PARAMETER;
  }
  if (filter_expression == nullptr) {
    // Only the parameters change (ContentFilteredTopic::set_expression_parameters): ours have none.
    return filter_instance != nullptr ? ReturnCode_t::RETCODE_OK : ReturnCode_t::RETCODE_BAD_PARAMETER;
  }
  std::lock_guard<std::mutex> lock(mutex_);
  auto it = filters_.find(filter_expression);
  if (it != filters_.end()) {
    filter_instance = it->second;  // one of this participant's readers
    return ReturnCode_t::RETCODE_OK;
  }
  if (!steps_class || type_name == nullptr) {
    return ReturnCode_t::RETCODE_BAD_PARAMETER;
  }
  // A remote reader's: evaluated by a writer of this participant. An expression that is not
  // ours (another program using the class name) is refused: Fast DDS then filters nothing for it.
  const std::string expression(filter_expression);
  const std::optional<StepNeeds> needs = StepNeeds::parse(expression.substr(0, expression.find('|')));
  dds::TypeSupport type = types_ ? types_(type_name) : dds::TypeSupport();
  if (!needs || type.empty()) {
    return ReturnCode_t::RETCODE_BAD_PARAMETER;
  }
  auto filter = std::make_unique<ReaderKeyFilter>(type, type_name, ReaderKeyFilter::Side::kWriter);
  filter->read_only(*needs);
  filter_instance = filter.get();
  writer_side_.emplace(filter_instance, std::move(filter));
  return ReturnCode_t::RETCODE_OK;
}

ReturnCode_t KeyFilterFactory::delete_content_filter(const char* /*filter_class_name*/,
                                                     dds::IContentFilter* filter_instance) {
  std::lock_guard<std::mutex> lock(mutex_);
  writer_side_.erase(filter_instance);  // the bus owns its readers' filters
  return ReturnCode_t::RETCODE_OK;
}

}  // namespace robodds
