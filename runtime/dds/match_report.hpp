#pragma once
// What a participant knows about its peers and the match state of its own endpoints, kept to
// explain a lockstep timeout: which topics have no matched peer and which QoS are incompatible,
// with both sides' policies (runtime-internal; includes Fast DDS).

#include <fastdds/dds/core/policy/QosPolicies.hpp>
#include <fastdds/dds/domain/DomainParticipantListener.hpp>
#include <fastdds/rtps/common/Guid.h>

#include <atomic>
#include <condition_variable>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "runtime/bus/peer_losses.hpp"
#include "runtime/bus/run_digest.hpp"
#include "runtime/dds/send_batch.hpp"

namespace robodds {
namespace dds = eprosima::fastdds::dds;
namespace rtps = eprosima::fastrtps::rtps;

/// What discovery told this participant about its peers: participant names (so that reports can
/// say which host a writer lives on) and the QoS each remote endpoint offers or requests per
/// topic (so that an incompatible-QoS report shows both sides). Filled by Fast DDS's discovery
/// thread; only stores, never calls back into DDS.
class PeerDirectory : public dds::DomainParticipantListener {
 public:
  void on_participant_discovery(dds::DomainParticipant*, rtps::ParticipantDiscoveryInfo&& info) override;
  void on_publisher_discovery(dds::DomainParticipant*, rtps::WriterDiscoveryInfo&& info) override;
  void on_subscriber_discovery(dds::DomainParticipant*, rtps::ReaderDiscoveryInfo&& info) override;
  /// DDS Security: a discovered participant passed (or failed) the PKI-DH handshake and access
  /// control; only then does it exchange endpoints and crypto tokens with this one.
  void onParticipantAuthentication(dds::DomainParticipant*, rtps::ParticipantAuthenticationInfo&& info) override;

  /// "'control'" for a participant named "robodds-control" (the host names participants
  /// "robodds-<group>"), another participant's full name, or its GUID prefix if not yet known.
  std::string who(const rtps::GUID_t& guid) const;

  /// Remote endpoints of `topic` whose QoS differs from `local` (the suspects of a mismatch;
  /// all of them if none differs), e.g. "BEST_EFFORT/TRANSIENT_LOCAL from 'control'".
  std::string remote_qos(const std::string& topic, bool of_writers, const std::string& local) const;

  std::size_t participants_alive() const;
  /// Participants that went away (lease expired: dropped; goodbye: left), oldest first
  /// (PeerLossSource, for the host's loss watch).
  std::vector<PeerLoss> losses() const;
  std::size_t loss_count() const { return loss_count_.load(); }
  /// Whether a participant of that name is alive now (PeerLossSource::participant_alive).
  bool alive_named(const std::string& name) const;
  /// The names of every participant discovered so far (also those dropped since), sorted.
  std::vector<std::string> discovered_names() const;

  /// Secure runs: the discovered participants whose authentication has not succeeded (yet), as
  /// who() spells them, e.g. "'control', 'sim'"; empty when all did or the run is not secure (`secure`: this participant
  /// has DDS Security on, so every peer must authenticate).
  std::string unauthenticated() const;
  void set_secure(bool secure);

  /// The remote endpoints of `topic` discovered so far, e.g. "'control'", or "" if none.
  std::string discovered(const std::string& topic, bool of_writers) const;

  /// SampleMeta::writer_id of a writer GUID (a hash of its 16 bytes), remembered so that
  /// writer_name() can spell it later.
  std::uint64_t writer_id(const rtps::GUID_t& writer);
  /// "'control' (writer 01.0f...|0.0.1.3)" for an id writer_id() returned; "writer <id>" otherwise.
  std::string writer_name(std::uint64_t id) const;
  /// This participant's own GUID prefix and the components it announces (its writers' process).
  void set_self(const rtps::GuidPrefix_t& prefix, std::vector<std::string> components);
  /// Whether the process of writer `id` (an id writer_id() returned) announced one of
  /// `components` (component_announcement.hpp): false for an unknown writer, or a participant
  /// that announced nothing. A participant whose discovery was not reported yet (its writer's
  /// first sample can overtake the callback) is waited for, at most kParticipantWaitMs.
  static constexpr int kParticipantWaitMs = 500;
  bool writer_runs_any(std::uint64_t id, const std::vector<std::string>& components) const;

  /// This participant's run and the digest of what its host loaded (runtime/bus/run_digest.hpp);
  /// call before discovery starts. A participant that announces the same run with another digest
  /// counts as announcing no component: its writers are no scenario producer here.
  void set_run(std::uint64_t run_id, const RunDigest& digest);
  /// Bus::peer_digests(): the participants discovered so far (also those gone since) that
  /// announced run `run_id` with a digest.
  std::vector<PeerDigest> peer_digests(std::uint64_t run_id) const;
  /// Grows at every participant discovered, changed or gone.
  std::uint64_t generation() const { return generation_.load(); }

 private:
  using Table = std::map<std::string, std::map<std::string, std::pair<std::string, rtps::GUID_t>>>;
  std::string who_locked(const std::string& guid_prefix_key) const;  // who(), mutex_ held
  void remember(Table& table, const std::string& topic, const rtps::GUID_t& guid, bool present, const std::string& qos);

  mutable std::mutex mutex_;
  mutable std::condition_variable participant_discovered_;  // names_ grew
  std::map<std::string, std::string> names_;  // GUID prefix -> participant name
  std::set<std::string> alive_;
  bool secure_ = false;
  std::set<std::string> authenticated_;  // GUID prefixes
  Table writers_;
  Table readers_;
  std::map<std::uint64_t, rtps::GUID_t> writer_guids_;  // writer_id() -> GUID
  std::map<std::string, std::vector<std::string>> components_;  // GUID prefix -> announced components
  std::vector<PeerLoss> losses_;
  std::atomic<std::size_t> loss_count_{0};  // losses_.size(), read without the mutex
  struct RunAnnounced {
    std::uint64_t run_id = 0;
    std::map<std::string, std::string> digest;
  };
  std::map<std::string, RunAnnounced> runs_;  // GUID prefix -> its announced run and digest
  std::optional<std::uint64_t> own_run_;
  std::map<std::string, std::string> own_digest_;
  std::atomic<std::uint64_t> generation_{0};
  // The unicast locators of the alive participants that announced robodds components: send
  // batches go only to those (send_batch.hpp).
  BatchingPeers batching_peers_;
};

/// Match state of one local endpoint, kept for the report appended to lockstep timeouts. The
/// remote side of an incompatibility is looked up when the text is built, not when Fast DDS
/// reports it: the incompatible-QoS callback can come before discovery reports the remote QoS.
class MatchState {
 public:
  MatchState(std::string topic, bool reader, const PeerDirectory* peers)
      : topic_(std::move(topic)), reader_(reader), peers_(peers) {}

  std::atomic<int> matched{0};

  void set_incompatible(dds::QosPolicyId_t policy, std::string local_qos);
  /// e.g. "incompatible QoS RELIABILITY: this reader requests RELIABLE/..., writers offer
  /// BEST_EFFORT/... from 'control'"; empty if no incompatibility was reported.
  std::string incompatible() const;
  /// e.g. "sim/clock (reader): no writer matched" or "sim/step_done (writer): incompatible QoS ..."; empty when
  /// matched and compatible. An incompatible QoS explains a missing match, so it wins over "no match".
  std::string problem() const;

 private:
  std::string topic_;
  bool reader_;
  const PeerDirectory* peers_;
  mutable std::mutex mutex_;
  bool incompatible_ = false;
  dds::QosPolicyId_t policy_ = dds::INVALID_QOS_POLICY_ID;
  std::string local_qos_;
};

/// One line for Bus::match_report: how many peers were discovered, then the problem of each of
/// `endpoints` that has one; empty when none has.
std::string describe_match_problems(const PeerDirectory& peers, const std::vector<const MatchState*>& endpoints);

}  // namespace robodds
