// apply_peer_lease(): the participant lease our hosts announce unless the profile sets its own
// (issue 24, finding 6: a dead host is known to the others within 2 s). grow_shm_segments(): the
// segment a lockstep host needs for its window (runtime/launch/shm_segment.hpp).

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

TEST(ShmSegments, GrowsEverySharedMemoryTransportOnACopyAndLeavesTheRest) {
  dds::DomainParticipantQos qos;
  auto udp = std::make_shared<UDPv4TransportDescriptor>();
  auto shm = std::make_shared<SharedMemTransportDescriptor>();
  shm->segment_size(512 * 1024);
  shm->port_queue_capacity(8192);
  qos.transport().user_transports = {udp, shm};
  grow_shm_segments(qos, 2 * 1024 * 1024);
  EXPECT_EQ(qos.transport().user_transports.at(0), udp);
  EXPECT_EQ(shm_of(qos, 1).segment_size(), 2U * 1024 * 1024);
  EXPECT_EQ(shm_of(qos, 1).port_queue_capacity(), 8192U);  // the rest of the descriptor is kept
  EXPECT_EQ(shm->segment_size(), 512U * 1024);             // the profile's descriptor is not touched
}

TEST(ShmSegments, NeverShrinksALargerSegment) {
  dds::DomainParticipantQos qos;
  auto shm = std::make_shared<SharedMemTransportDescriptor>();
  shm->segment_size(4 * 1024 * 1024);
  qos.transport().user_transports = {shm};
  grow_shm_segments(qos, 1024 * 1024);
  EXPECT_EQ(qos.transport().user_transports.at(0), shm);
  EXPECT_EQ(shm_of(qos, 0).segment_size(), 4U * 1024 * 1024);
}

}  // namespace
}  // namespace robodds
