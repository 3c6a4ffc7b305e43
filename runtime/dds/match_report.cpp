#include "runtime/dds/match_report.hpp"

#include <algorithm>
#include <sstream>

#include "runtime/dds/component_announcement.hpp"
#include "runtime/dds/text.hpp"
#include "runtime/bus/bus.hpp"
#include "runtime/base/log.hpp"

namespace robodds {
namespace {

/// Where a participant receives unicast (user data and discovery): what a send batch to it goes to.
std::vector<rtps::Locator_t> unicast_locators(const rtps::ParticipantProxyData& participant) {
  std::vector<rtps::Locator_t> locators(participant.default_locators.unicast.begin(), participant.default_locators.unicast.end());
  locators.insert(locators.end(), participant.metatraffic_locators.unicast.begin(), participant.metatraffic_locators.unicast.end());
  return locators;
}

}  // namespace

void PeerDirectory::on_participant_discovery(dds::DomainParticipant*, rtps::ParticipantDiscoveryInfo&& info) {
  const std::string name = info.info.m_participantName.to_string();
  const std::string key = guid_prefix_text(info.info.m_guid.guidPrefix);
  std::lock_guard<std::mutex> lock(mutex_);
  switch (info.status) {
    case rtps::ParticipantDiscoveryInfo::DISCOVERED_PARTICIPANT:
    case rtps::ParticipantDiscoveryInfo::CHANGED_QOS_PARTICIPANT: {
      if (info.status == rtps::ParticipantDiscoveryInfo::DISCOVERED_PARTICIPANT &&
          std::any_of(losses_.begin(), losses_.end(), [&name](const PeerLoss& loss) { return loss.participant == name; })) {
        // Back after a drop (a cut link restored) or a restart: its endpoints match again as new ones.
        log::info("dds", "participant '" + name + "' discovered again after it was lost");
      }
      names_[key] = name;
      alive_.insert(key);
      const std::vector<std::uint8_t> user_data(info.info.m_userData.begin(), info.info.m_userData.end());
      std::optional<Announcement> announced = parse_announcement(user_data);
      if (announced) {  // a robodds participant (also one that loaded other files): it splits batches
        batching_peers_.set(key, unicast_locators(info.info));
      } else {
        batching_peers_.erase(key);
      }
      runs_.erase(key);
      if (announced && announced->run_id) {
        runs_[key] = RunAnnounced{*announced->run_id, announced->digest};
      }
      // A host of this run that loaded other files produces nothing here (docs/deployment.md,
      // "Multi-host by hand"): its writers are refused as unknown producers.
      const bool other_files = announced && own_run_ && announced->run_id == own_run_ && !own_digest_.empty() &&
                               !announced->digest.empty() && announced->digest != own_digest_;
      if (announced && !other_files) {
        components_[key] = std::move(announced->components);
      } else {
        components_.erase(key);
      }
      ++generation_;
      participant_discovered_.notify_all();
      break;
    }
    case rtps::ParticipantDiscoveryInfo::DROPPED_PARTICIPANT:
      // Dropped = its lease expired without a goodbye: the host died or its network did.
      log::warn("dds", "participant '" + name + "' dropped: no announcement within its lease (host or network down?)");
      alive_.erase(key);
      batching_peers_.erase(key);
      if (!secure_ || authenticated_.count(key) != 0) {  // an unauthenticated participant is no lost host
        losses_.push_back(PeerLoss{name, true, monotonic_now_ns()});
        loss_count_ = losses_.size();
      }
      ++generation_;
      break;
    case rtps::ParticipantDiscoveryInfo::REMOVED_PARTICIPANT:
      log::debug("dds", "participant '" + name + "' left");
      alive_.erase(key);
      batching_peers_.erase(key);
      if (!secure_ || authenticated_.count(key) != 0) {
        losses_.push_back(PeerLoss{name, false, monotonic_now_ns()});
        loss_count_ = losses_.size();
      }
      ++generation_;
      break;
    default:
      break;
  }
}

void PeerDirectory::on_publisher_discovery(dds::DomainParticipant*, rtps::WriterDiscoveryInfo&& info) {
  const auto& q = info.info.m_qos;
  remember(writers_, info.info.topicName().to_string(), info.info.guid(),
           info.status != rtps::WriterDiscoveryInfo::REMOVED_WRITER,
           describe_qos(q.m_reliability, q.m_durability, q.m_deadline, q.m_liveliness));
}

void PeerDirectory::on_subscriber_discovery(dds::DomainParticipant*, rtps::ReaderDiscoveryInfo&& info) {
  const auto& q = info.info.m_qos;
  remember(readers_, info.info.topicName().to_string(), info.info.guid(),
           info.status != rtps::ReaderDiscoveryInfo::REMOVED_READER,
           describe_qos(q.m_reliability, q.m_durability, q.m_deadline, q.m_liveliness));
}

void PeerDirectory::onParticipantAuthentication(dds::DomainParticipant*, rtps::ParticipantAuthenticationInfo&& info) {
  const std::string key = guid_prefix_text(info.guid.guidPrefix);
  const bool authorized = info.status == rtps::ParticipantAuthenticationInfo::AUTHORIZED_PARTICIPANT;
  log::debug("dds", "DDS Security: participant " + key + (authorized ? " authenticated" : " refused (authentication failed)"));
  std::lock_guard<std::mutex> lock(mutex_);
  if (authorized) {
    authenticated_.insert(key);
  } else {
    authenticated_.erase(key);
  }
  ++generation_;  // its digest counts from now on (peer_digests)
}

void PeerDirectory::set_secure(bool secure) {
  std::lock_guard<std::mutex> lock(mutex_);
  secure_ = secure;
}

std::string PeerDirectory::unauthenticated() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::string out;
  if (!secure_) {
    return out;
  }
  for (const std::string& key : alive_) {
    if (authenticated_.count(key) == 0) {
      out += (out.empty() ? "" : ", ") + who_locked(key);
    }
  }
  return out;
}

std::string PeerDirectory::discovered(const std::string& topic, bool of_writers) const {
  std::vector<rtps::GUID_t> found;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto& table = of_writers ? writers_ : readers_;
    auto it = table.find(topic);
    if (it != table.end()) {
      for (const auto& [guid_key, entry] : it->second) {
        found.push_back(entry.second);
      }
    }
  }
  std::string out;
  for (const rtps::GUID_t& guid : found) {
    out += (out.empty() ? "" : ", ") + who(guid);
  }
  return out;
}

std::uint64_t PeerDirectory::writer_id(const rtps::GUID_t& writer) {
  // FNV-1a over prefix and entity id: stable for the writer's life, the same in every process.
  std::uint64_t hash = 1469598103934665603ULL;
  const auto mix = [&hash](std::uint8_t byte) {
    hash ^= byte;
    hash *= 1099511628211ULL;
  };
  for (std::uint8_t byte : writer.guidPrefix.value) {
    mix(byte);
  }
  for (std::uint8_t byte : writer.entityId.value) {
    mix(byte);
  }
  hash = hash == 0 ? 1 : hash;  // 0 means "unknown" in SampleMeta
  std::lock_guard<std::mutex> lock(mutex_);
  writer_guids_.emplace(hash, writer);
  return hash;
}

std::string PeerDirectory::writer_name(std::uint64_t id) const {
  rtps::GUID_t guid;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = writer_guids_.find(id);
    if (it == writer_guids_.end()) {
      return "writer " + std::to_string(id);
    }
    guid = it->second;
  }
  std::ostringstream entity;
  entity << guid.entityId;
  return who(guid) + " (writer " + guid_prefix_text(guid.guidPrefix) + "|" + entity.str() + ")";
}

void PeerDirectory::set_self(const rtps::GuidPrefix_t& prefix, std::vector<std::string> components) {
  std::lock_guard<std::mutex> lock(mutex_);
  components_[guid_prefix_text(prefix)] = std::move(components);
}

void PeerDirectory::set_run(std::uint64_t run_id, const RunDigest& digest) {
  std::lock_guard<std::mutex> lock(mutex_);
  own_run_ = run_id;
  own_digest_.clear();
  for (const DigestEntry& entry : digest) {
    own_digest_[entry.label] = entry.digest;
  }
}

std::vector<PeerDigest> PeerDirectory::peer_digests(std::uint64_t run_id) const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<PeerDigest> peers;
  for (const auto& [key, run] : runs_) {
    // Gone ones too: a host that loaded other files and left at once (it found the difference
    // first) still was a host of this run.
    // Secure runs: a participant that did not authenticate is no host of this run, whatever its
    // user data says (anyone can announce one: a foreign CA's host would otherwise end the run).
    const bool trusted = !secure_ || authenticated_.count(key) != 0;
    if (trusted && run.run_id == run_id && !run.digest.empty()) {
      peers.push_back(PeerDigest{who_locked(key), run.digest});
    }
  }
  return peers;
}

bool PeerDirectory::writer_runs_any(std::uint64_t id, const std::vector<std::string>& components) const {
  std::unique_lock<std::mutex> lock(mutex_);
  const auto writer = writer_guids_.find(id);
  if (writer == writer_guids_.end()) {
    return false;
  }
  const std::string key = guid_prefix_text(writer->second.guidPrefix);
  participant_discovered_.wait_for(lock, std::chrono::milliseconds(kParticipantWaitMs),
                                   [&] { return names_.count(key) != 0 || components_.count(key) != 0; });
  const auto announced = components_.find(key);
  if (announced == components_.end()) {
    return false;
  }
  for (const std::string& component : components) {
    if (std::find(announced->second.begin(), announced->second.end(), component) != announced->second.end()) {
      return true;
    }
  }
  return false;
}

std::string PeerDirectory::who(const rtps::GUID_t& guid) const {
  const std::string key = guid_prefix_text(guid.guidPrefix);
  std::lock_guard<std::mutex> lock(mutex_);
  return who_locked(key);
}

std::string PeerDirectory::who_locked(const std::string& key) const {
  auto it = names_.find(key);
  if (it == names_.end()) {
    return "participant " + key;
  }
  const std::string& name = it->second;
  return "'" + (name.rfind("robodds-", 0) == 0 ? name.substr(8) : name) + "'";
}

std::string PeerDirectory::remote_qos(const std::string& topic, bool of_writers, const std::string& local) const {
  std::vector<std::pair<std::string, rtps::GUID_t>> found;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto& table = of_writers ? writers_ : readers_;
    auto it = table.find(topic);
    if (it != table.end()) {
      for (const auto& [guid_key, entry] : it->second) {
        found.push_back(entry);
      }
    }
  }
  const bool any_differs = std::any_of(found.begin(), found.end(), [&](const auto& e) { return e.first != local; });
  std::string out;
  for (const auto& [qos, guid] : found) {
    if (!any_differs || qos != local) {
      out += (out.empty() ? "" : ", ") + qos + " from " + who(guid);
    }
  }
  return out.empty() ? std::string("(not discovered yet)") : out;
}

std::vector<std::string> PeerDirectory::discovered_names() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<std::string> names;
  for (const auto& [prefix, name] : names_) {
    names.push_back(name);
  }
  std::sort(names.begin(), names.end());
  return names;
}

bool PeerDirectory::alive_named(const std::string& name) const {
  std::lock_guard<std::mutex> lock(mutex_);
  return std::any_of(alive_.begin(), alive_.end(), [&](const std::string& key) {
    const auto it = names_.find(key);
    return it != names_.end() && it->second == name;
  });
}

std::vector<PeerLoss> PeerDirectory::losses() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return losses_;
}

std::size_t PeerDirectory::participants_alive() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return alive_.size();
}

void PeerDirectory::remember(Table& table, const std::string& topic, const rtps::GUID_t& guid, bool present,
                             const std::string& qos) {
  std::ostringstream key;
  key << guid;
  std::lock_guard<std::mutex> lock(mutex_);
  if (present) {
    table[topic][key.str()] = {qos, guid};
  } else {
    table[topic].erase(key.str());
  }
}

void MatchState::set_incompatible(dds::QosPolicyId_t policy, std::string local_qos) {
  std::lock_guard<std::mutex> lock(mutex_);
  policy_ = policy;
  local_qos_ = std::move(local_qos);
  incompatible_ = true;
}

std::string MatchState::incompatible() const {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!incompatible_) {
    return "";
  }
  return "incompatible QoS " + policy_name(policy_) + (reader_ ? ": this reader requests " : ": this writer offers ") +
         local_qos_ + (reader_ ? ", writers offer " : ", readers request ") + peers_->remote_qos(topic_, reader_, local_qos_);
}

std::string MatchState::problem() const {
  const std::string what = topic_ + (reader_ ? " (reader)" : " (writer)");
  const std::string incompatibility = incompatible();
  if (!incompatibility.empty()) {
    return what + ": " + incompatibility;
  }
  if (matched == 0) {
    // A remote endpoint that discovery reported but that never matched: with DDS Security, the
    // pair's crypto tokens were not (yet) exchanged.
    const std::string seen = peers_->discovered(topic_, reader_);
    return what + (reader_ ? ": no writer matched" : ": no reader matched") +
           (seen.empty() ? std::string() : " (discovered: " + seen + ")");
  }
  return "";
}

std::string describe_match_problems(const PeerDirectory& peers, const std::vector<const MatchState*>& endpoints) {
  std::vector<std::string> problems;
  for (const MatchState* endpoint : endpoints) {
    std::string problem = endpoint->problem();
    if (!problem.empty()) {
      problems.push_back(std::move(problem));
    }
  }
  if (problems.empty()) {
    return "";
  }
  const std::size_t alive = peers.participants_alive();
  std::string out = alive == 0 ? "DDS: no other participant discovered (another domain id, multicast blocked, "
                                 "or discovery server unreachable?)"
                               : "DDS: " + std::to_string(alive) + " other participant(s) discovered";
  const std::string unauthenticated = peers.unauthenticated();
  if (!unauthenticated.empty()) {
    out += "; DDS Security: not authenticated (yet): " + unauthenticated;
  }
  for (const std::string& problem : problems) {
    out += "; " + problem;
  }
  return out;
}

}  // namespace robodds
