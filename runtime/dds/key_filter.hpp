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
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "runtime/bus/bus.hpp"
#include "runtime/bus/sample_key.hpp"
#include "runtime/bus/step_needs.hpp"

namespace robodds {

/// The filter of one reader: the key rules of its subscribers, and the steps they read
/// (StepNeeds: newest-only lockstep inputs). A sample passes when a subscriber has no rule (it
/// takes every key) or a rule takes its key, otherwise every subscriber's `refused` is called
/// and the sample is dropped; then, with read_only(), when it is needed at a read step. A payload
/// that does not decode is dropped too (the type support counts it as undecodable, as a take would).
///
/// The steps, unlike the key rules, are also evaluated by the writers (class
/// KeyFilterFactory::kStepClass, registered by every robodds participant; the expression names
/// them): a robodds writer then sends the reader only the samples it needs, and a GAP for the
/// others. Fast DDS' reader trusts the writer's verdict (the filter's signature in the sample's
/// inline QoS) and evaluates nothing, keys included: a robodds writer writes only the keys of its
/// run's robots, and any other writer's samples (which carry no verdict) still meet both checks here.
class ReaderKeyFilter final : public eprosima::fastdds::dds::IContentFilter {
 public:
  /// Where the filter is evaluated: by the reader (every check, a payload that does not decode
  /// dropped), or for a remote reader by a writer of this participant (steps only; a payload that
  /// does not decode passes: the reader judges it).
  enum class Side { kReader, kWriter };
  /// `type`: the registered type support of the reader's topic (decodes the payload);
  /// `type_name`: its IDL name (the instance key and header step functions).
  ReaderKeyFilter(eprosima::fastdds::dds::TypeSupport type, const std::string& type_name, Side side = Side::kReader);
  ~ReaderKeyFilter();
  ReaderKeyFilter(const ReaderKeyFilter&) = delete;
  ReaderKeyFilter& operator=(const ReaderKeyFilter&) = delete;

  /// A subscriber that takes only the keys `filter` takes.
  void add(KeyFilter filter);
  /// A subscriber that takes every key: from now on every sample passes.
  void add_unfiltered();
  /// Whether any subscriber has a key rule and none takes every key (a content filter is worth it).
  bool filters() const;
  /// From now on only samples `needs` names pass (every subscriber reads only those).
  void read_only(const StepNeeds& needs);

  /// Fast DDS calls it per received sample, under the RTPS reader's lock (one call at a time per
  /// reader), before the history sees the sample.
  bool evaluate(const SerializedPayload& payload, const FilterSampleInfo& sample_info,
                const GUID_t& reader_guid) const override;

  /// Samples dropped so far (refused keys and undecodable payloads).
  std::uint64_t dropped() const { return dropped_.load(std::memory_order_relaxed); }
  /// Samples left out so far because no read step needs them.
  std::uint64_t left_out() const { return left_out_.load(std::memory_order_relaxed); }

 private:
  /// Whether a rule takes the decoded sample's key; calls every `refused` when none does. Call with mutex_ held.
  bool takes_key() const;
  /// Whether a read step needs the decoded `sample` (counts it left out if not). Call with mutex_ held.
  bool passes_steps(const void* sample) const;

  eprosima::fastdds::dds::TypeSupport type_;
  SampleKeyFunction key_;
  SampleStepsFunction steps_;
  Side side_;
  mutable std::mutex mutex_;  // guards the members below; never held while Fast DDS is called
  std::vector<KeyFilter> rules_;
  std::size_t unfiltered_ = 0;
  std::optional<StepNeeds> needs_;  // read_only()
  mutable SerializedPayload scratch_;  // a copy of the payload: the type support writes into it
  void* sample_ = nullptr;             // the decoded sample
  mutable std::atomic<std::uint64_t> dropped_{0};
  mutable std::atomic<std::uint64_t> left_out_{0};
};

/// Marks, for its lifetime, the sample this thread is writing through a DataWriter (the bus's
/// writer sets it around DataWriter::write), with its type's sample_steps_function(), which also
/// tells the type (one function per IDL type). Fast DDS 2.9 evaluates the
/// writer-side filters of remote readers inside that write(), on the writing thread, once for the
/// change it just encoded from this sample (ReaderFilterCollection::update_filter_info); a
/// ReaderKeyFilter on the writer side then reads the steps from the sample instead of decoding the
/// payload again (the decode was ~5 % of a 200-robot plant's write time, on a strict lockstep
/// step's critical path). `sample` must outlive the mark.
class SampleBeingWritten {
 public:
  SampleBeingWritten(const void* sample, SampleStepsFunction steps_of_type);
  ~SampleBeingWritten();
  SampleBeingWritten(const SampleBeingWritten&) = delete;
  SampleBeingWritten& operator=(const SampleBeingWritten&) = delete;
  /// The sample this thread is writing if its type is the one of `steps_of_type`, else null.
  static const void* of_type(SampleStepsFunction steps_of_type);

 private:
  // The mark this one hides, restored at its end (a write inside a write: none today).
  const void* outer_sample_;
  SampleStepsFunction outer_steps_of_type_;
};

/// The content filter factory of one participant, for two filter classes:
/// - class_name(), unique per participant: the readers' key filters. No other participant knows
///   it, so none evaluates it writer-side: every sample is judged by the reader's own filter.
/// - kStepClass, the same in every robodds participant: readers whose subscribers read only some
///   steps. Its expression starts with StepNeeds::text() (then '|' and what makes it unique);
///   a writer of this participant matched with such a remote reader evaluates the steps
///   (ReaderKeyFilter::Side::kWriter, made here and owned by this factory).
/// Registered under both names (register_content_filter_factory).
class KeyFilterFactory : public eprosima::fastdds::dds::IContentFilterFactory {
 public:
  static constexpr const char* kStepClass = "robodds.steps";
  /// `types`: the type support registered under an IDL type name (a null one when none is).
  KeyFilterFactory(std::string class_name, std::function<eprosima::fastdds::dds::TypeSupport(const std::string&)> types)
      : class_name_(std::move(class_name)), types_(std::move(types)) {}
  KeyFilterFactory(const KeyFilterFactory&) = delete;
  KeyFilterFactory& operator=(const KeyFilterFactory&) = delete;
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
  std::function<eprosima::fastdds::dds::TypeSupport(const std::string&)> types_;
  std::mutex mutex_;
  std::map<std::string, ReaderKeyFilter*> filters_;
  // Made by create_content_filter() for remote readers, deleted by delete_content_filter().
  std::map<const eprosima::fastdds::dds::IContentFilter*, std::unique_ptr<ReaderKeyFilter>> writer_side_;
};

}  // namespace robodds
