#pragma once
// Loading and checking the QoS profile files (runtime-internal; includes Fast DDS). The
// Fast-DDS-free entry points (load_qos_files, required_data_profiles) are declared in
// runtime/dds/dds_bus.hpp.

#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>

#include "runtime/dds/dds_bus.hpp"

namespace robodds {

/// Loads options.qos_files and returns the participant QoS of options.participant_profile,
/// checked; ConfigError naming the file and element if it is missing or unusable.
eprosima::fastdds::dds::DomainParticipantQos checked_participant_qos(const DdsOptions& options);

}  // namespace robodds
