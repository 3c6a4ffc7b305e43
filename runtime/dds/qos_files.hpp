#pragma once
// Loading and checking the QoS profile files (runtime-internal; includes Fast DDS). The
// Fast-DDS-free entry points (load_qos_files, check_qos_profiles) are declared in
// runtime/dds/dds_bus.hpp.

#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>
#include <fastdds/dds/publisher/qos/DataWriterQos.hpp>

#include "runtime/dds/dds_bus.hpp"

namespace robodds {

/// The participant lease our hosts announce (s): the other participants drop one that was silent
/// this long (killed, frozen, its network down), so a dead host is known within it (issue 24,
/// finding 6: within 2 s). Announced every kPeerAnnouncementS, so two lost announcements in a
/// row are not a death. The shipped profiles (deploy/qos) set both; a profile that sets no lease
/// (Fast DDS's default, 20 s) gets them from apply_peer_lease(); a profile that sets one keeps it.
inline constexpr double kPeerLeaseS = 1.5;
inline constexpr double kPeerAnnouncementS = 0.5;
/// Sets kPeerLeaseS/kPeerAnnouncementS unless `qos` has a lease other than Fast DDS's default.
void apply_peer_lease(eprosima::fastdds::dds::DomainParticipantQos& qos);

/// The writer QoS of `profile` that Fast DDS 2.9.1's XML parser cannot express, applied to `qos`
/// (read from that profile); deploy/qos/robodds_qos.xml says it next to the profile. `lockstep`:
/// no piggyback heartbeats (DataWriterQos::reliable_writer_qos().disable_heartbeat_piggyback).
void apply_writer_qos_beyond_xml(const std::string& profile, eprosima::fastdds::dds::DataWriterQos& qos);

/// Grows every shared-memory transport of `qos` to a segment of at least `bytes` and every UDPv4
/// transport to a receive buffer of at least `bytes` (DdsOptions::transport_buffer_bytes), on
/// copies of the profile's descriptors. Returns whether a UDP receive buffer grew.
bool grow_transport_buffers(eprosima::fastdds::dds::DomainParticipantQos& qos, std::size_t bytes);
/// The kernel's limit on a socket's receive buffer (/proc/sys/net/core/rmem_max), nullopt if unreadable.
std::optional<std::size_t> kernel_receive_buffer_max();
/// Logs once per process, naming both figures and the sysctl, when `kernel_max` is below `bytes`:
/// Fast DDS asks for the buffer and the kernel silently caps it.
void warn_if_kernel_caps_receive_buffer(std::size_t bytes, std::optional<std::size_t> kernel_max);

/// Loads options.qos_files, checks every required profile (check_qos_profiles) and returns the
/// participant QoS of options.participant_profile, checked; ConfigError naming the file and
/// element if a profile is missing or unusable. Creates no participant.
eprosima::fastdds::dds::DomainParticipantQos checked_participant_qos(const DdsOptions& options);

/// The first error Fast DDS logged since the last call (e.g. why it refused a participant or a
/// writer: its cause; the later lines repeat it), empty if none.
std::string take_dds_errors();

}  // namespace robodds
