#include "runtime/bus/run_digest.hpp"

#include <algorithm>
#include <cctype>

namespace robodds {
namespace {

/// The first 16 hex digits: enough to tell two digests apart in a message.
std::string short_digest(const std::string& digest) { return digest.substr(0, 16) + (digest.size() > 16 ? "..." : ""); }

/// What an entry is: "scenario file", "run options", "QoS file", ... by the kind before its ':'.
std::string noun(const std::string& label) {
  const std::string kind = label.substr(0, label.find(':'));
  return kind == "scenario"     ? "scenario file"
         : kind == "options"    ? "run options (--seed, --duration, --set)"
         : kind == "qos"        ? "QoS file"
         : kind == "governance" ? "security governance file"
         : kind == "params"     ? "--params file"
                                : "'" + label + "'";
}

/// The file name in a label "kind:name" (empty for "scenario" and "options").
std::string name_in(const std::string& label) {
  const std::size_t colon = label.find(':');
  return colon == std::string::npos ? std::string() : " '" + label.substr(colon + 1) + "'";
}

std::map<std::string, std::string> entries_of(const RunDigest& digest) {
  std::map<std::string, std::string> entries;
  for (const DigestEntry& e : digest) {
    entries[e.label] = e.digest;
  }
  return entries;
}

}  // namespace

bool digest_label_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '.' || c == '_' || c == ':' || c == '-';
}

std::string sanitised_digest_label(std::string label) {
  for (char& c : label) {
    if (!digest_label_char(c)) {
      c = '_';
    }
  }
  return label;
}

std::string digest_label(const std::string& kind, const std::string& name) { return sanitised_digest_label(kind + ":" + name); }

std::string digest_difference(const RunDigest& own, const PeerDigest& peer) {
  for (const DigestEntry& entry : own) {
    const auto theirs = peer.entries.find(entry.label);
    if (theirs == peer.entries.end()) {
      return "host " + peer.host + " did not load the " + noun(entry.label) + " " + entry.source + " that this host loaded";
    }
    if (theirs->second != entry.digest) {
      return "host " + peer.host + " loaded a different " + noun(entry.label) + " than this host's " + entry.source + " (sha256 " +
             short_digest(entry.digest) + " here, " + short_digest(theirs->second) + " there)";
    }
  }
  const std::map<std::string, std::string> mine = entries_of(own);
  for (const auto& [label, digest] : peer.entries) {
    if (mine.count(label) == 0) {
      return "host " + peer.host + " loaded a " + noun(label) + name_in(label) + " that this host did not load";
    }
  }
  return {};
}

DigestVerdict judge_digests(const RunDigest& own, const std::vector<PeerDigest>& peers) {
  DigestVerdict verdict;
  std::vector<std::pair<std::map<std::string, std::string>, std::size_t>> others;  // each other digest, its hosts
  for (const PeerDigest& peer : peers) {
    const std::string difference = digest_difference(own, peer);
    if (difference.empty()) {
      ++verdict.agreeing;
      continue;
    }
    if (verdict.difference.empty()) {
      verdict.difference = difference;
    }
    verdict.differing_hosts.push_back(peer.host);
    auto same = std::find_if(others.begin(), others.end(), [&peer](const auto& o) { return o.first == peer.entries; });
    if (same == others.end()) {
      others.emplace_back(peer.entries, 1);
    } else {
      ++same->second;
    }
  }
  for (const auto& other : others) {
    verdict.largest_other = std::max(verdict.largest_other, other.second);
  }
  return verdict;
}

}  // namespace robodds
