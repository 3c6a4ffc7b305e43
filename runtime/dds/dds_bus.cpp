#include "runtime/dds/dds_bus.hpp"
#include "runtime/dds/participant_topics.hpp"

#include "runtime/dds/component_announcement.hpp"

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/qos/DataWriterQos.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/ContentFilteredTopic.hpp>
#include <fastdds/dds/topic/Topic.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include <algorithm>
#include <chrono>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "runtime/dds/dds_sample_codec.hpp"
#include "runtime/dds/key_filter.hpp"
#include "runtime/dds/listeners.hpp"
#include "runtime/dds/match_report.hpp"
#include "runtime/dds/participant.hpp"
#include "runtime/dds/qos_files.hpp"
#include "runtime/dds/text.hpp"
#include "runtime/base/error.hpp"
#include "runtime/bus/instance_spread.hpp"
#include "runtime/base/log.hpp"
#include "runtime/bus/qos_profiles.hpp"
#include "runtime/dds/send_batch.hpp"
#include "runtime/bus/sample_key.hpp"
#include "runtime/topics/topic_catalog.hpp"
#include "runtime/health/shutdown_watchdog.hpp"
#include "runtime/dds/type_support.hpp"
#include "runtime/dds/undecodable.hpp"

namespace robodds {
namespace dds = eprosima::fastdds::dds;
using eprosima::fastrtps::types::ReturnCode_t;

namespace {

/// One topic's writer. In lockstep with many robots, several DataWriters of the topic, each
/// publishing its share of the instances (runtime/bus/instance_spread.hpp); the first one carries
/// the listener (matches, incompatible QoS: the others have the same QoS and readers).
class DdsWriter : public WriterHandle {
 public:
  /// `wait_to_forget`: lockstep (simulated time may wait): end_instance() waits for the
  /// acknowledgements; real time never blocks a loop and retries at each later write instead.
  DdsWriter(std::vector<dds::DataWriter*> writers, const std::string& type_name, std::string topic,
            const MatchState* match, bool wait_to_forget)
      : writers_(std::move(writers)),
        key_(sample_key_function(type_name)),
        steps_(sample_steps_function(type_name)),
        spread_(writers_.size()),
        forget_pending_(writers_.size(), false),
        wait_to_forget_(wait_to_forget),
        topic_(std::move(topic)),
        match_(match) {}
  void write(const void* sample) override {
    std::lock_guard<std::mutex> lock(mutex_);
    if (any_forget_pending_) {
      forget_acknowledged(std::chrono::milliseconds(0));
    }
    const SampleBeingWritten writing(sample, steps_);  // for the writer-side step filters
    if (!writers_[writer_of(sample)]->write(const_cast<void*>(sample))) {
      throw RunError("DDS write failed on topic " + topic_);
    }
  }
  /// Fast DDS 2.9.1 cannot drop one instance's samples safely: unregister_instance() removes them
  /// from inside StatefulWriter::check_acked_status()'s walk over the history, whose iterator the
  /// removal invalidates (seen here: the writer's receive thread spinning there for good, the
  /// participant silent). So the DataWriter that carried the ended instance empties its whole
  /// history once every matched reader has acknowledged all of it: those readers lose nothing;
  /// only a reader matching later misses the last samples (the live instances' next samples
  /// come at their next step). Kept histories are what transient-local lockstep needs at the
  /// start, when readers may match after the first samples; by the time an instance ends, every
  /// reader of the run has matched.
  void end_instance(const void* sample) override {
    std::lock_guard<std::mutex> lock(mutex_);
    forget_pending_[writer_of(sample)] = true;
    any_forget_pending_ = true;
    forget_acknowledged(wait_to_forget_ ? kForgetWait : std::chrono::milliseconds(0));
  }
  /// Histories emptied by end_instance() so far.
  std::uint64_t histories_forgotten() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return forgotten_;
  }
  const std::string& topic() const override { return topic_; }
  /// Every DataWriter of the topic, within one `timeout` in all.
  bool wait_acknowledged(std::chrono::milliseconds timeout) override {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    bool all = true;
    for (dds::DataWriter* writer : writers_) {
      const auto left = std::max(std::chrono::nanoseconds(0), deadline - std::chrono::steady_clock::now());
      const eprosima::fastrtps::Duration_t limit(std::chrono::duration<double>(left).count());
      all = writer->wait_for_acknowledgments(limit) == ReturnCode_t::RETCODE_OK && all;
    }
    return all;
  }
  bool has_matched_readers() const override { return match_->matched.load(std::memory_order_relaxed) > 0; }
  const std::vector<dds::DataWriter*>& writers() const { return writers_; }

 private:
  /// How long a lockstep writer waits for the acknowledgements of an ended instance's samples
  /// before it leaves the history for a later write to empty (a reader that does not answer).
  static constexpr std::chrono::milliseconds kForgetWait{1000};

  /// The number of the DataWriter that publishes the instance of `sample` (always the same one).
  /// Call with mutex_ held.
  std::size_t writer_of(const void* sample) { return writers_.size() == 1 ? 0 : spread_.writer_of(key_(sample)); }

  /// Empties each DataWriter with an ended instance whose samples every matched reader has
  /// acknowledged within `wait`. Call with mutex_ held (no write in between).
  void forget_acknowledged(std::chrono::milliseconds wait) {
    any_forget_pending_ = false;
    for (std::size_t i = 0; i < writers_.size(); ++i) {
      if (!forget_pending_[i]) {
        continue;
      }
      const eprosima::fastrtps::Duration_t limit(std::chrono::duration<double>(wait).count());
      if (writers_[i]->wait_for_acknowledgments(limit) == ReturnCode_t::RETCODE_OK) {
        std::size_t removed = 0;
        writers_[i]->clear_history(&removed);
        forget_pending_[i] = false;
        ++forgotten_;
        log::debug("dds", topic_ + ": an instance ended; the writer's history (" + std::to_string(removed) +
                              " acknowledged samples) emptied");
      } else {
        any_forget_pending_ = true;
      }
    }
  }

  std::vector<dds::DataWriter*> writers_;  // owned by the participant
  SampleKeyFunction key_;                  // idl::instance_key of the topic's type (used with several writers)
  SampleStepsFunction steps_;              // the header steps of the topic's type (SampleBeingWritten)
  // spread_ and the forgetting below: a writer may be used from several threads, and no sample
  // may be written between a writer's acknowledgement check and the emptying of its history.
  mutable std::mutex mutex_;
  InstanceSpread spread_;
  std::vector<bool> forget_pending_;  // per DataWriter: an instance ended, the history not yet emptied
  bool any_forget_pending_ = false;
  bool wait_to_forget_;
  std::uint64_t forgotten_ = 0;
  std::string topic_;
  const MatchState* match_;  // the first writer's listener's: matched readers now
};

/// One subscriber of a DDS reader: what it reads (set_step_needs) goes to the bus' record of it.
class DdsReader : public ReaderHandle {
 public:
  explicit DdsReader(std::function<void(const StepNeeds&)> on_needs) : on_needs_(std::move(on_needs)) {}
  void set_step_needs(const StepNeeds& needs) override { on_needs_(needs); }

 private:
  std::function<void(const StepNeeds&)> on_needs_;
};

class FastDdsBus : public DdsBus, public PeerLossSource {
 public:
  explicit FastDdsBus(const DdsOptions& options) {
    // Every profile this bus can ask for is checked before the participant exists: a bad QoS file
    // creates nothing. Anything that throws after create_participant() leaves participant_ to
    // delete what was built (it is declared after what its listeners point to).
    dds::DomainParticipantQos qos = checked_participant_qos(options);
    qos.name(options.participant_name);
    const std::vector<std::uint8_t> announcement = component_announcement(options.components, options.run_id, options.digest);
    qos.user_data().data_vec(std::vector<eprosima::fastrtps::rtps::octet>(announcement.begin(), announcement.end()));
    peers_.set_secure(!options.security_dir.empty());
    if (options.run_id) {
      peers_.set_run(*options.run_id, options.digest);
    }
    // Only discovery callbacks (participant names, remote QoS): with an empty mask no entity
    // status reaches this listener, so on_data_available stays with the readers' listeners.
    participant_ = create_participant(options.domain_id, qos, &peers_, dds::StatusMask::none(), options.participant_profile);
    peers_.set_self(participant_->guid().guidPrefix, options.components);
    // A class name no other participant knows: our readers' filters are never evaluated by a
    // writer (Fast DDS does so for a writer whose participant registered the same class).
    dds::DomainParticipant* participant = participant_.get();
    key_filters_ = std::make_unique<KeyFilterFactory>("robodds.keys." + guid_prefix_text(participant_->guid().guidPrefix),
                                                      [participant](const std::string& type_name) { return participant->find_type(type_name); });
    // The step class is every robodds participant's: its writers evaluate the steps remote readers need.
    if (participant_->register_content_filter_factory(key_filters_->class_name().c_str(), key_filters_.get()) !=
            ReturnCode_t::RETCODE_OK ||
        participant_->register_content_filter_factory(KeyFilterFactory::kStepClass, key_filters_.get()) !=
            ReturnCode_t::RETCODE_OK) {
      throw RunError("could not register the key filter factory on domain " + std::to_string(options.domain_id));
    }
    publisher_ = participant_->create_publisher(dds::PUBLISHER_QOS_DEFAULT);
    subscriber_ = participant_->create_subscriber(dds::SUBSCRIBER_QOS_DEFAULT);
    if (publisher_ == nullptr || subscriber_ == nullptr) {
      throw RunError("could not create a DDS publisher and subscriber on domain " + std::to_string(options.domain_id));
    }
  }

  // The readers first (close_readers() waits for a callback in progress), then participant_
  // deletes the other entities and itself before the listeners and peers_ die.
  // Histories are emptied before participant_ deletes the writers (see clear_writer_histories()).
  ~FastDdsBus() override {
    close_readers();
    clear_writer_histories();
  }

  std::shared_ptr<WriterHandle> writer(const std::string& topic, const std::string& type_name, const std::string& profile) override {
    std::lock_guard<std::mutex> lock(mutex_);
    const std::string key = topic + "|" + profile;
    auto it = writers_.find(key);
    if (it != writers_.end()) {
      return it->second;
    }
    dds::Topic* dds_topic = ensure_topic(topic, type_name);
    auto listener = std::make_unique<WriterListener>(topic, &peers_);
    dds::StatusMask mask = dds::StatusMask::offered_incompatible_qos() << dds::StatusMask::publication_matched();
    dds::DataWriter* writer = nullptr;
    auto owned = exclusive_.find(topic);
    dds::DataWriterQos qos;
    if (publisher_->get_datawriter_qos_from_profile(profile, qos) == ReturnCode_t::RETCODE_OK) {
      apply_writer_qos_beyond_xml(profile, qos);
      if (owned != exclusive_.end()) {
        qos.ownership().kind = dds::EXCLUSIVE_OWNERSHIP_QOS;
        qos.ownership_strength().value = owned->second;
      }
      writer = publisher_->create_datawriter(dds_topic, qos, listener.get(), mask);
    }
    std::vector<dds::DataWriter*> writers;
    const std::size_t spread = writers_per_topic(topic, profile, owned != exclusive_.end());
    while (writer != nullptr) {
      writers.push_back(writer);
      writer = writers.size() < spread ? publisher_->create_datawriter(dds_topic, qos, nullptr, dds::StatusMask::none()) : nullptr;
    }
    if (writers.size() < spread) {
      const std::string reasons = take_dds_errors();  // e.g. DDS Security: not allowed by the permissions
      for (dds::DataWriter* created : writers) {
        publisher_->delete_datawriter(created);  // none may outlive `listener`
      }
      throw ConfigError("cannot create a writer on " + topic + " with QoS profile '" + profile + "'" +
                        (reasons.empty() ? std::string() : ": Fast DDS: " + reasons));
    }
    if (spread > 1) {
      log::debug("dds", topic + ": " + std::to_string(spread) + " writers (profile '" + profile + "', " +
                            std::to_string(expected_robots_) + " robots, at most " +
                            std::to_string(kRobotsPerLockstepWriter) + " each)");
    }
    auto handle = std::make_shared<DdsWriter>(std::move(writers), type_name, topic, &listener->match(),
                                              profile == kLockstepProfile);
    writer_listeners_[key] = std::move(listener);
    writers_[key] = handle;
    return handle;
  }

  void expect_robots(std::size_t robots) override {
    std::lock_guard<std::mutex> lock(mutex_);
    expected_robots_ = robots;
  }

  std::optional<std::size_t> writer_history_depth(const std::string& profile) const override {
    dds::DataWriterQos qos;
    if (publisher_->get_datawriter_qos_from_profile(profile, qos) != ReturnCode_t::RETCODE_OK ||
        qos.history().kind != dds::KEEP_LAST_HISTORY_QOS) {
      return std::nullopt;
    }
    return static_cast<std::size_t>(qos.history().depth);
  }

  std::shared_ptr<ReaderHandle> reader(const std::string& topic, const std::string& type_name, const std::string& profile,
                                       SampleCallback on_sample, ReaderEventCallback on_event) override {
    return add_reader(topic, type_name, profile, std::move(on_sample), std::move(on_event), std::nullopt);
  }

  std::shared_ptr<ReaderHandle> filtered_reader(const std::string& topic, const std::string& type_name,
                                                const std::string& profile, SampleCallback on_sample,
                                                ReaderEventCallback on_event, KeyFilter filter) override {
    return add_reader(topic, type_name, profile, std::move(on_sample), std::move(on_event), std::move(filter));
  }

  void start() override {
    std::lock_guard<std::mutex> lock(mutex_);
    started_ = true;
    for (auto& [key, pending] : readers_) {
      create_reader(pending);
    }
  }

  void close_readers() override {
    std::lock_guard<std::mutex> lock(mutex_);
    ShutdownWatchdog watchdog("deleting the DDS readers (each waits for its callback in progress)");
    for (auto& [key, pending] : readers_) {
      if (pending.reader != nullptr) {
        // Waits for a callback in progress on this reader (Fast DDS takes the reader's lock).
        subscriber_->delete_datareader(pending.reader);
        pending.reader = nullptr;
      }
    }
    started_ = false;  // a reader() call after this must not resurrect readers
  }

  // One deadline for all writers (not `timeout` each: with a peer gone, every reliable writer
  // would wait it out in turn). A signal meanwhile ends the process (shutting_down()).
  // Fast DDS 2.9 deletes a writer by releasing its history's samples one by one, each under the
  // writer's lock but while they are still in the history (RTPSWriter::deinit(); Fast-DDS#4076,
  // fixed in 2.13). A periodic heartbeat between two releases (every 10 ms while a reader has not
  // acknowledged, e.g. one of a SIGKILLed peer, matched until its lease ends) sees the released
  // samples' sequence number 0 as a hole before the first kept one and counts gaps up to it
  // across 2^64 numbers, holding the writer's lock: the deleting thread waits forever (seen with
  // gdb: StatefulWriter::add_gaps_for_holes_in_history_ spinning, ~StatefulWriter in
  // RTPSWriter::release_change). clear_history() removes all samples in one go under that lock,
  // so deinit() has none left to release.
  void clear_writer_histories() {
    std::lock_guard<std::mutex> lock(mutex_);
    ShutdownWatchdog watchdog("emptying the DDS writers' histories");
    for (auto& [key, writer] : writers_) {
      std::size_t removed = 0;
      for (dds::DataWriter* each : writer->writers()) {
        each->clear_history(&removed);  // RETCODE_ERROR when it was empty already
      }
    }
  }

  std::uint64_t samples_left_out_on_arrival() const override {
    std::lock_guard<std::mutex> lock(mutex_);
    std::uint64_t total = 0;
    for (const auto& [key, pending] : readers_) {
      total += pending.key_filter->left_out();
    }
    return total;
  }

  void begin_write_batch() override { open_send_batch(); }
  void end_write_batch() override { close_send_batch(); }

  void flush(std::chrono::milliseconds timeout) override {
    std::lock_guard<std::mutex> lock(mutex_);
    ShutdownWatchdog watchdog("waiting for the acknowledgement of the last samples", timeout + shutdown_limit());
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    for (auto& [key, writer] : writers_) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
      if (left.count() <= 0) {
        break;
      }
      writer->wait_acknowledged(left);
    }
  }

  std::string match_report() override {
    std::lock_guard<std::mutex> lock(mutex_);
    // Readers first, then writers; a reader closed by close_readers() has nothing to report.
    std::vector<const MatchState*> endpoints;
    for (const auto& [key, pending] : readers_) {
      if (pending.reader != nullptr) {
        endpoints.push_back(&pending.listener->match());
      }
    }
    for (const auto& [key, listener] : writer_listeners_) {
      endpoints.push_back(&listener->match());
    }
    return describe_match_problems(peers_, endpoints);
  }

  std::string writer_name(std::uint64_t writer_id) const override { return peers_.writer_name(writer_id); }
  std::vector<PeerDigest> peer_digests(std::uint64_t run_id) const override { return peers_.peer_digests(run_id); }
  std::uint64_t discovery_generation() const override { return peers_.generation(); }
  bool writer_runs_any(std::uint64_t writer_id, const std::vector<std::string>& components) const override {
    return peers_.writer_runs_any(writer_id, components);
  }

  std::optional<std::vector<std::string>> discovered_participants() const override { return peers_.discovered_names(); }
  std::size_t peer_loss_count() const override { return peers_.loss_count(); }
  std::vector<PeerLoss> peer_losses() const override { return peers_.losses(); }
  bool participant_alive(const std::string& participant) const override { return peers_.alive_named(participant); }

  /// The type support counts per type (it does not know the topic); each of our topics is
  /// credited with its type's count. A process reading several topics of one type (e.g. the
  /// RelativePoseEstimate topics of paper 3) shows their sum on each of them.
  std::map<std::string, std::uint64_t> undecodable_samples() const override {
    std::lock_guard<std::mutex> lock(mutex_);
    std::map<std::string, std::uint64_t> counts;
    for (const auto& [key, pending] : readers_) {
      const std::uint64_t n = robodds::undecodable_samples(pending.type_name);
      if (n > 0) {
        counts[pending.topic] = n;
      }
    }
    return counts;
  }

  void set_exclusive_ownership(const std::string& topic, std::uint32_t writer_strength) override {
    std::lock_guard<std::mutex> lock(mutex_);
    exclusive_[topic] = writer_strength;
  }

 private:
  struct PendingReader {
    std::string topic;
    std::string type_name;
    std::string profile;
    std::unique_ptr<ReaderListener> listener;
    // The subscribers' key rules (Bus::KeyFilter) and read steps; Fast DDS evaluates it through filtered_topic.
    std::unique_ptr<ReaderKeyFilter> key_filter;
    // Per subscriber, in the order they came: the steps it reads (ReaderHandle::set_step_needs),
    // nullopt while it reads every sample.
    std::vector<std::optional<StepNeeds>> step_needs;
    dds::ContentFilteredTopic* filtered_topic = nullptr;  // owned by participant_; made once
    dds::DataReader* reader = nullptr;
  };

  /// reader() and filtered_reader(): one DDS reader per (topic, profile), a callback per call.
  std::shared_ptr<ReaderHandle> add_reader(const std::string& topic, const std::string& type_name, const std::string& profile,
                                           SampleCallback on_sample, ReaderEventCallback on_event,
                                           std::optional<KeyFilter> filter) {
    std::lock_guard<std::mutex> lock(mutex_);
    const std::string key = topic + "|" + profile;
    auto it = readers_.find(key);
    if (it == readers_.end()) {
      ensure_topic(topic, type_name);
      PendingReader pending;
      pending.topic = topic;
      pending.type_name = type_name;
      pending.profile = profile;
      pending.listener = std::make_unique<ReaderListener>(type_name, topic, &peers_);
      pending.key_filter = std::make_unique<ReaderKeyFilter>(participant_->find_type(type_name), type_name);
      it = readers_.emplace(key, std::move(pending)).first;
    }
    // A reader made before a subscriber without a rule joins keeps its content filter, which
    // then passes every sample (ReaderKeyFilter::evaluate).
    if (filter) {
      it->second.key_filter->add(std::move(*filter));
    } else {
      it->second.key_filter->add_unfiltered();
    }
    it->second.listener->add(std::move(on_sample), std::move(on_event));
    const std::size_t subscriber = it->second.step_needs.size();
    it->second.step_needs.emplace_back();
    if (started_) {
      create_reader(it->second);
    }
    return std::make_shared<DdsReader>([this, key, subscriber](const StepNeeds& needs) {
      std::lock_guard<std::mutex> lock(mutex_);
      readers_.at(key).step_needs.at(subscriber) = needs;  // read when the reader is made (start())
    });
  }

  /// The steps every subscriber of `pending` reads, when each said (set_step_needs) and some
  /// sample is needed by none; nullopt otherwise.
  static std::optional<StepNeeds> reader_step_needs(const PendingReader& pending) {
    if (pending.step_needs.empty()) {
      return std::nullopt;
    }
    std::optional<StepNeeds> all;
    for (const std::optional<StepNeeds>& needs : pending.step_needs) {
      if (!needs) {
        return std::nullopt;
      }
      if (!all) {
        all = *needs;
      } else {
        all->add(*needs);
      }
    }
    return all->all() ? std::nullopt : all;
  }

  /// The topic a reader reads: the topic itself, or a ContentFilteredTopic of it evaluated by the
  /// reader's ReaderKeyFilter (key_filter.hpp): of the step class, evaluated by remote writers
  /// too, when every subscriber reads only some steps; else of this participant's key class when
  /// every subscriber so far has a key rule.
  dds::TopicDescription* topic_to_read(PendingReader& pending) {
    const std::optional<StepNeeds> needs = reader_step_needs(pending);
    if (pending.filtered_topic == nullptr && needs) {
      // Evaluated by the writers too (KeyFilterFactory::kStepClass): the expression names the
      // steps, then what makes it this participant's (a ContentFilteredTopic name is unique in it).
      pending.key_filter->read_only(*needs);
      const std::string name = needs->text() + "|" + pending.topic + "|" + pending.profile + "|" +
                               guid_prefix_text(participant_->guid().guidPrefix);
      key_filters_->add(name, pending.key_filter.get());
      pending.filtered_topic = participant_->create_contentfilteredtopic(name, topics_.at(pending.topic), name, {},
                                                                         KeyFilterFactory::kStepClass);
      if (pending.filtered_topic == nullptr) {
        throw RunError("could not create the step filter of topic " + pending.topic + ": Fast DDS: " + take_dds_errors());
      }
      log::debug("dds", pending.topic + ": reads only " + needs->text() + " (its writers leave out the other samples)");
    }
    if (pending.filtered_topic == nullptr && pending.key_filter->filters()) {
      // Not a name of any DDS topic ('|' is in none of ours); also the filter's expression.
      const std::string name = pending.topic + "|keys|" + pending.profile;
      key_filters_->add(name, pending.key_filter.get());
      pending.filtered_topic = participant_->create_contentfilteredtopic(name, topics_.at(pending.topic), name, {},
                                                                         key_filters_->class_name().c_str());
      if (pending.filtered_topic == nullptr) {
        throw RunError("could not create the key filter of topic " + pending.topic + ": Fast DDS: " + take_dds_errors());
      }
    }
    if (pending.filtered_topic != nullptr) {
      return pending.filtered_topic;
    }
    return topics_.at(pending.topic);
  }

  void create_reader(PendingReader& pending) {
    if (pending.reader != nullptr) {
      return;
    }
    dds::StatusMask mask = dds::StatusMask::data_available() << dds::StatusMask::requested_incompatible_qos()
                           << dds::StatusMask::requested_deadline_missed() << dds::StatusMask::liveliness_changed()
                           << dds::StatusMask::subscription_matched();
    dds::TopicDescription* topic = topic_to_read(pending);
    if (exclusive_.count(pending.topic) == 0) {
      pending.reader = subscriber_->create_datareader_with_profile(topic, pending.profile, pending.listener.get(), mask);
    } else {
      dds::DataReaderQos qos;
      if (subscriber_->get_datareader_qos_from_profile(pending.profile, qos) == ReturnCode_t::RETCODE_OK) {
        qos.ownership().kind = dds::EXCLUSIVE_OWNERSHIP_QOS;
        pending.reader = subscriber_->create_datareader(topic, qos, pending.listener.get(), mask);
      }
    }
    if (pending.reader == nullptr) {
      const std::string reasons = take_dds_errors();
      throw ConfigError("cannot create a reader on " + pending.topic + " with QoS profile '" + pending.profile + "'" +
                        (reasons.empty() ? std::string() : ": Fast DDS: " + reasons));
    }
  }

  /// How many DataWriters publish one topic: several only for a topic keyed by robot (its first
  /// key member is robot_id: one instance per robot, or per robot and peer) in the `lockstep`
  /// profile (the deep history; runtime/bus/instance_spread.hpp), without exclusive ownership.
  std::size_t writers_per_topic(const std::string& topic, const std::string& profile, bool exclusive) const {
    const TopicInfo* info = find_topic(topic);
    const bool robot_keyed = info != nullptr && info->key.rfind("robot_id", 0) == 0;
    return profile == kLockstepProfile && !exclusive && robot_keyed ? writers_for_robots(expected_robots_) : 1;
  }

  dds::Topic* ensure_topic(const std::string& topic, const std::string& type_name) {
    return topics_.ensure(*participant_, topic, type_name, [](const std::string& name) { return make_type_support(name); });
  }

  // What the participant and its entities call into: declared before participant_, so that they
  // outlive it (members die in reverse order, also when the constructor throws).
  PeerDirectory peers_;
  std::unique_ptr<KeyFilterFactory> key_filters_;  // registered on participant_ by its class name
  mutable std::mutex mutex_;
  std::map<std::string, std::unique_ptr<WriterListener>> writer_listeners_;
  std::map<std::string, PendingReader> readers_;
  ParticipantTopics topics_;
  std::map<std::string, std::shared_ptr<DdsWriter>> writers_;
  std::map<std::string, std::uint32_t> exclusive_;  // topic -> ownership strength of its writers here
  ParticipantPtr participant_;
  dds::Publisher* publisher_ = nullptr;    // owned by participant_
  dds::Subscriber* subscriber_ = nullptr;  // owned by participant_
  bool started_ = false;
  std::size_t expected_robots_ = 1;  // expect_robots()
};

}  // namespace

std::unique_ptr<DdsBus> make_dds_bus(const DdsOptions& options) {
  install_dds_sample_codec();  // before any component is configured: a recorder or a replay source needs it
  return std::make_unique<FastDdsBus>(options);
}

}  // namespace robodds
