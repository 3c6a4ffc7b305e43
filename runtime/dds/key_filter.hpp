#pragma once
// The key filter of a DDS reader (runtime-internal; includes Fast DDS): drops a sample whose
// instance key no local subscriber of the reader takes (Bus::KeyFilter) inside Fast DDS, before
// the reader's history creates an instance for it.
//
// Why a content filter: Fast DDS 2.9 evaluates a reader's content filter in the RTPS reader
// (StatelessReader/StatefulReader::processDataMsg), before the sample reaches the DataReader's
// history. Without it every key ever received became an instance of that history for good, each
// with its deadline, which DataReaderImpl re-arms per instance and finds by a walk over all
// instances: a 20,000-key flood kept receivers at 35-47 % CPU after it ended (issue 24,
// finding 4; docs/security.md, "Floods"). A content filter is the one hook Fast DDS offers
// before the history. max_instances alone would not do: once foreign keys fill the slots, an
// instance is only replaced when it is no longer alive, so legitimate robots would be locked out
// for as long as the flooding writer lives.

#include <fastdds/dds/topic/IContentFilter.hpp>
#include <fastdds/dds/topic/IContentFilterFactory.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include <atomic>
#include <cstdint>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "runtime/bus/bus.hpp"
#include "runtime/bus/sample_key.hpp"

namespace robodds {

/// The filter of one reader: the key rules of its subscribers. A sample passes when a subscriber
/// has no rule (it takes every key) or a rule takes its key; otherwise every subscriber's
/// `refused` is called and the sample is dropped. A payload that does not decode is dropped too
/// (the type support counts it as undecodable, as a take would).
class ReaderKeyFilter : public eprosima::fastdds::dds::IContentFilter {
 public:
  /// `type`: the registered type support of the reader's topic (decodes the payload);
  /// `type_name`: its IDL name (the instance key function).
  ReaderKeyFilter(eprosima::fastdds::dds::TypeSupport type, const std::string& type_name);
  ~ReaderKeyFilter();
  ReaderKeyFilter(const ReaderKeyFilter&) = delete;
  ReaderKeyFilter& operator=(const ReaderKeyFilter&) = delete;

  /// A subscriber that takes only the keys `filter` takes.
  void add(KeyFilter filter);
  /// A subscriber that takes every key: from now on every sample passes.
  void add_unfiltered();
  /// Whether any subscriber has a key rule and none takes every key (a content filter is worth it).
  bool filters() const;

  /// Fast DDS calls it per received sample, under the RTPS reader's lock (one call at a time per
  /// reader), before the history sees the sample.
  bool evaluate(const SerializedPayload& payload, const FilterSampleInfo& sample_info,
                const GUID_t& reader_guid) const override;

  /// Samples dropped so far (refused keys and undecodable payloads).
  std::uint64_t dropped() const { return dropped_.load(std::memory_order_relaxed); }

 private:
  eprosima::fastdds::dds::TypeSupport type_;
  SampleKeyFunction key_;
  mutable std::mutex mutex_;  // guards the members below; never held while Fast DDS is called
  std::vector<KeyFilter> rules_;
  std::size_t unfiltered_ = 0;
  mutable SerializedPayload scratch_;  // a copy of the payload: the type support writes into it
  void* sample_ = nullptr;             // the decoded sample
  mutable std::atomic<std::uint64_t> dropped_{0};
};

/// The content filter factory of one participant: hands Fast DDS the ReaderKeyFilter registered
/// under a filter expression (the topic name). Its class name is unique per participant
/// (class_name()), so no other participant can evaluate it writer-side: every sample is judged
/// by the reader's own filter.
class KeyFilterFactory : public eprosima::fastdds::dds::IContentFilterFactory {
 public:
  explicit KeyFilterFactory(std::string class_name) : class_name_(std::move(class_name)) {}
  const std::string& class_name() const { return class_name_; }
  /// `filter` (owned by the caller, alive as long as the participant) for `expression`.
  void add(const std::string& expression, ReaderKeyFilter* filter);

  ReturnCode_t create_content_filter(const char* filter_class_name, const char* type_name,
                                     const eprosima::fastdds::dds::TopicDataType* data_type, const char* filter_expression,
                                     const ParameterSeq& filter_parameters,
                                     eprosima::fastdds::dds::IContentFilter*& filter_instance) override;
  ReturnCode_t delete_content_filter(const char* filter_class_name,
                                     eprosima::fastdds::dds::IContentFilter* filter_instance) override;

 private:
  std::string class_name_;
  std::mutex mutex_;
  std::map<std::string, ReaderKeyFilter*> filters_;
};

}  // namespace robodds
