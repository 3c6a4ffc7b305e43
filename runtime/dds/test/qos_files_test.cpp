// apply_peer_lease(): the participant lease our hosts announce unless the profile sets its own
// (issue 24, finding 6: a dead host is known to the others within 2 s). grow_transport_buffers(): the
// segment and UDP receive buffer a lockstep host needs for its window (runtime/launch/transport_buffers.hpp).

#include "runtime/dds/qos_files.hpp"

#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>
#include <fastdds/dds/publisher/qos/DataWriterQos.hpp>
#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <fastdds/rtps/transport/shared_mem/SharedMemTransportDescriptor.h>
#include <gtest/gtest.h>

#include <memory>

namespace robodds {
namespace {
namespace dds = eprosima::fastdds::dds;

TEST(PeerLease, AProfileWithoutALeaseGetsOurs) {
  dds::DomainParticipantQos qos;  // Fast DDS's defaults: 20 s lease, 3 s announcements
  apply_peer_lease(qos);
  const auto& discovery = qos.wire_protocol().builtin.discovery_config;
  EXPECT_EQ(discovery.leaseDuration, eprosima::fastrtps::Duration_t(1, 500000000));
  EXPECT_EQ(discovery.leaseDuration_announcementperiod, eprosima::fastrtps::Duration_t(0, 500000000));
}

TEST(PeerLease, AProfileThatSetsALeaseKeepsIt) {
  dds::DomainParticipantQos qos;
  auto& discovery = qos.wire_protocol().builtin.discovery_config;
  discovery.leaseDuration = eprosima::fastrtps::Duration_t(5, 0);
  discovery.leaseDuration_announcementperiod = eprosima::fastrtps::Duration_t(1, 0);
  apply_peer_lease(qos);
  EXPECT_EQ(discovery.leaseDuration, eprosima::fastrtps::Duration_t(5, 0));
  EXPECT_EQ(discovery.leaseDuration_announcementperiod, eprosima::fastrtps::Duration_t(1, 0));
}

TEST(WriterQosBeyondXml, LockstepWritersSendNoPiggybackHeartbeatsOthersKeepTheDefault) {
  dds::DataWriterQos lockstep;
  apply_writer_qos_beyond_xml(kLockstepProfile, lockstep);
  EXPECT_TRUE(lockstep.reliable_writer_qos().disable_heartbeat_piggyback);
  for (const char* profile : {"state", "command", "mission", "lockstep_local", "monitor"}) {
    dds::DataWriterQos qos;
    apply_writer_qos_beyond_xml(profile, qos);
    EXPECT_FALSE(qos.reliable_writer_qos().disable_heartbeat_piggyback) << profile;
  }
}

using eprosima::fastdds::rtps::SharedMemTransportDescriptor;
using eprosima::fastdds::rtps::UDPv4TransportDescriptor;

const SharedMemTransportDescriptor& shm_of(const dds::DomainParticipantQos& qos, std::size_t i) {
  return dynamic_cast<const SharedMemTransportDescriptor&>(*qos.transport().user_transports.at(i));
}

const UDPv4TransportDescriptor& udp_of(const dds::DomainParticipantQos& qos, std::size_t i) {
  return dynamic_cast<const UDPv4TransportDescriptor&>(*qos.transport().user_transports.at(i));
}

TEST(TransportBuffers, GrowsTheSegmentAndTheUdpReceiveBufferOnCopies) {
  dds::DomainParticipantQos qos;
  auto udp = std::make_shared<UDPv4TransportDescriptor>();  // receiveBufferSize 0: the kernel's default
  udp->non_blocking_send = true;
  auto shm = std::make_shared<SharedMemTransportDescriptor>();
  shm->segment_size(512 * 1024);
  shm->port_queue_capacity(8192);
  qos.transport().user_transports = {udp, shm};
  EXPECT_TRUE(grow_transport_buffers(qos, 2 * 1024 * 1024));
  EXPECT_EQ(udp_of(qos, 0).receiveBufferSize, 2U * 1024 * 1024);
  EXPECT_TRUE(udp_of(qos, 0).non_blocking_send);  // the rest of each descriptor is kept
  EXPECT_EQ(shm_of(qos, 1).segment_size(), 2U * 1024 * 1024);
  EXPECT_EQ(shm_of(qos, 1).port_queue_capacity(), 8192U);
  EXPECT_EQ(udp->receiveBufferSize, 0U);  // the profile's descriptors are not touched
  EXPECT_EQ(shm->segment_size(), 512U * 1024);
}

TEST(TransportBuffers, NeverShrinksALargerOneAndSaysWhetherAUdpBufferGrew) {
  dds::DomainParticipantQos qos;
  auto shm = std::make_shared<SharedMemTransportDescriptor>();
  shm->segment_size(4 * 1024 * 1024);
  auto udp = std::make_shared<UDPv4TransportDescriptor>();
  udp->receiveBufferSize = 4 * 1024 * 1024;
  qos.transport().user_transports = {shm, udp};
  EXPECT_FALSE(grow_transport_buffers(qos, 1024 * 1024));
  EXPECT_EQ(qos.transport().user_transports.at(0), shm);
  EXPECT_EQ(qos.transport().user_transports.at(1), udp);
  dds::DomainParticipantQos shm_only;
  shm_only.transport().user_transports = {std::make_shared<SharedMemTransportDescriptor>()};
  EXPECT_FALSE(grow_transport_buffers(shm_only, 1024 * 1024));  // grown, but no UDP to warn about
  EXPECT_EQ(shm_of(shm_only, 0).segment_size(), 1024U * 1024);
}

TEST(TransportBuffers, AKernelLimitBelowTheRequestIsSaidOnceWithTheSysctl) {
  testing::internal::CaptureStderr();
  warn_if_kernel_caps_receive_buffer(1000, 2000);  // enough: nothing to say
  warn_if_kernel_caps_receive_buffer(1000, std::nullopt);
  warn_if_kernel_caps_receive_buffer(1740800, 212992);
  warn_if_kernel_caps_receive_buffer(1740800, 212992);  // once per process
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("UDP receive buffer: this host asks for 1740800 bytes"), std::string::npos) << err;
  EXPECT_NE(err.find("allows 212992 (net.core.rmem_max)"), std::string::npos) << err;
  EXPECT_NE(err.find("sysctl -w net.core.rmem_max=1740800"), std::string::npos) << err;
  EXPECT_EQ(err.find("UDP receive buffer", err.find("UDP receive buffer") + 1), std::string::npos) << "said twice: " << err;
}

TEST(TransportBuffers, TheKernelsLimitIsReadableHere) {
  const std::optional<std::size_t> max = kernel_receive_buffer_max();
  ASSERT_TRUE(max.has_value()) << "/proc/sys/net/core/rmem_max";
  EXPECT_GT(*max, 0U);
}

}  // namespace
}  // namespace robodds
