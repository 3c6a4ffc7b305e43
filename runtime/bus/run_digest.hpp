#pragma once
// What every host of one run must have read alike (docs/deployment.md, "Multi-host by hand"):
// the scenario file, the run's shared options (--seed, --duration, --set, --params) and the QoS
// and security governance files, each as a digest. Each host announces its digest to the others
// (runtime/dds/component_announcement.hpp) and compares theirs with its own (runtime/host/
// digest_check.hpp). Per-file entries let the error name the file that differs. The digests
// guard against accidents (a stale copy, an edited file), not against attackers: anyone on the
// domain can announce anything (docs/security.md).

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace robodds {

/// One input of the run: what it is ("scenario", "options", "qos:robodds_qos.xml", ...), where this host
/// read it (a path, or the options as text) and its digest (lower-case hex).
struct DigestEntry {
  std::string label;
  std::string source;
  std::string digest;
};
using RunDigest = std::vector<DigestEntry>;

/// What another host announced: its name as Bus::writer_name spells hosts ("'control'") and its
/// entries (label -> digest).
struct PeerDigest {
  std::string host;
  std::map<std::string, std::string> entries;
};

/// Whether `c` may stand in an announced label: [A-Za-z0-9._:-].
bool digest_label_char(char c);
/// `label` with every other character replaced by '_'.
std::string sanitised_digest_label(std::string label);
/// A label "kind:name", sanitised (sanitised_digest_label()), as announced.
std::string digest_label(const std::string& kind, const std::string& name);

/// One phrase naming the first input where `peer` differs from `own` (in `own`'s order, then the
/// labels only the peer has), e.g. "host 'estimation' loaded another scenario file than this
/// host's /x/s.yaml (sha256 1a2b3c4d... here, 5e6f7a8b... there)"; empty when they agree.
std::string digest_difference(const RunDigest& own, const PeerDigest& peer);

/// How the hosts of a run that this host has discovered relate to its own digest.
struct DigestVerdict {
  std::string difference;     // digest_difference() with the first host that differs; empty: all agree
  std::vector<std::string> differing_hosts;  // every host that differs, as PeerDigest::host
  std::size_t agreeing = 1;   // hosts with this host's digest, itself included
  std::size_t largest_other = 0;  // hosts sharing the most common other digest
  /// This host is outnumbered: more hosts agree on another digest than on its own (real time:
  /// the odd host refuses to start; a tie is not outnumbered).
  bool outnumbered() const { return largest_other > agreeing; }
};
DigestVerdict judge_digests(const RunDigest& own, const std::vector<PeerDigest>& peers);

}  // namespace robodds
