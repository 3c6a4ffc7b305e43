// apply_peer_lease(): the participant lease our hosts announce unless the profile sets its own
// (issue 24, finding 6: a dead host is known to the others within 2 s).

#include "runtime/dds/qos_files.hpp"

#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace robodds
