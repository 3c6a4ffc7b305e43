#pragma once
// Loading and checking the QoS profile files (runtime-internal; includes Fast DDS). The
// Fast-DDS-free entry points (load_qos_files, check_qos_profiles) are declared in
// runtime/dds/dds_bus.hpp.

#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>

#include "runtime/dds/dds_bus.hpp"

namespace robodds {

/// Loads options.qos_files, checks every required profile (check_qos_profiles) and returns the
/// participant QoS of options.participant_profile, checked; ConfigError naming the file and
/// element if a profile is missing or unusable. Creates no participant.
eprosima::fastdds::dds::DomainParticipantQos checked_participant_qos(const DdsOptions& options);

/// The first error Fast DDS logged since the last call (e.g. why it refused a participant or a
/// writer: its cause; the later lines repeat it), empty if none.
std::string take_dds_errors();

}  // namespace robodds
