#pragma once
// What a host announces in its participant's USER_DATA: the scenario components it runs, so that
// other hosts' inputs can tell a scenario's producer from any other writer (docs/architecture.md,
// "One producer per instance and hot standby"), and, for a host of a scenario run, its run id and
// the digests of what it loaded (runtime/bus/run_digest.hpp), so that hosts that read different
// files find out (docs/deployment.md, "Multi-host by hand"). Text, one item per line:
//   robodds-components:a,b
//   robodds-run:<run id>                       (optional)
//   robodds-digest:<label>=<hex>;<label>=<hex>  (optional, with robodds-run)
// Anyone may claim anything here: only DDS Security makes it an identity (docs/security.md).
// What another participant sends is untrusted: anything longer than kMaxAnnouncementBytes, or
// not exactly this shape, is no announcement of ours.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "runtime/bus/run_digest.hpp"

namespace robodds {

/// Bounds of what we parse (bytes, entries): ours are a few hundred bytes.
inline constexpr std::size_t kMaxAnnouncementBytes = 4096;
inline constexpr std::size_t kMaxDigestEntries = 32;

struct Announcement {
  std::vector<std::string> components;
  std::optional<std::uint64_t> run_id;
  std::map<std::string, std::string> digest;  // label -> lower-case hex; empty: none announced
};

/// The USER_DATA octets announcing `components`, and, with `run_id`, the run and `digest`.
/// Labels are sanitised (only [A-Za-z0-9._:-] kept, others become '_').
std::vector<std::uint8_t> component_announcement(const std::vector<std::string>& components,
                                                 std::optional<std::uint64_t> run_id = std::nullopt,
                                                 const RunDigest& digest = {});

/// The announcement in `user_data`; nullopt when it is no announcement of ours (or malformed).
std::optional<Announcement> parse_announcement(const std::vector<std::uint8_t>& user_data);

/// The components announced in `user_data`; nullopt when it is no announcement of ours.
std::optional<std::vector<std::string>> announced_components(const std::vector<std::uint8_t>& user_data);

}  // namespace robodds
