#pragma once
// What a host announces in its participant's USER_DATA: the scenario components it runs, so that
// other hosts' inputs can tell a scenario's producer from any other writer (docs/architecture.md,
// "One producer per instance and hot standby"). Text: "robodds-components:" then the names,
// comma-separated. Anyone may claim anything here: only DDS Security makes it an identity
// (docs/security.md).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace robodds {

/// The USER_DATA octets announcing `components`.
std::vector<std::uint8_t> component_announcement(const std::vector<std::string>& components);

/// The components announced in `user_data`; nullopt when it is no announcement of ours.
std::optional<std::vector<std::string>> announced_components(const std::vector<std::uint8_t>& user_data);

}  // namespace robodds
