#include "runtime/dds/match_report.hpp"

#include <fastdds/rtps/builtin/data/ParticipantProxyData.h>
#include <fastdds/rtps/builtin/data/WriterProxyData.h>
#include <fastdds/rtps/participant/ParticipantDiscoveryInfo.h>
#include <fastdds/rtps/writer/WriterDiscoveryInfo.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "runtime/bus/bus.hpp"

namespace robodds {
namespace {

rtps::GUID_t guid_of(std::uint8_t participant, std::uint8_t entity) {
  rtps::GUID_t guid;
  guid.guidPrefix.value[0] = participant;
  guid.entityId.value[3] = entity;
  return guid;
}

void discover(PeerDirectory& peers, const std::string& name, const rtps::GUID_t& guid) {
  rtps::RTPSParticipantAllocationAttributes allocation;
  rtps::ParticipantProxyData data(allocation);
  data.m_guid = guid;
  data.m_participantName = name;
  peers.on_participant_discovery(nullptr, rtps::ParticipantDiscoveryInfo(data));
}

void lose(PeerDirectory& peers, const std::string& name, const rtps::GUID_t& guid, bool dropped) {
  rtps::RTPSParticipantAllocationAttributes allocation;
  rtps::ParticipantProxyData data(allocation);
  data.m_guid = guid;
  data.m_participantName = name;
  rtps::ParticipantDiscoveryInfo info(data);
  info.status = dropped ? rtps::ParticipantDiscoveryInfo::DROPPED_PARTICIPANT : rtps::ParticipantDiscoveryInfo::REMOVED_PARTICIPANT;
  peers.on_participant_discovery(nullptr, std::move(info));
}

void authenticate(PeerDirectory& peers, const rtps::GUID_t& guid) {
  rtps::ParticipantAuthenticationInfo info;
  info.status = rtps::ParticipantAuthenticationInfo::AUTHORIZED_PARTICIPANT;
  info.guid = guid;
  peers.onParticipantAuthentication(nullptr, std::move(info));
}

const rtps::GUID_t kControl = guid_of(1, 0xc1);
const rtps::GUID_t kSim = guid_of(2, 0xc1);

TEST(MatchReport, ASecureTimeoutNamesThePeersNotAuthenticatedYet) {
  PeerDirectory peers;
  peers.set_secure(true);
  discover(peers, "robodds-control", kControl);
  discover(peers, "robodds-sim", kSim);
  authenticate(peers, kSim);
  EXPECT_EQ(peers.unauthenticated(), "'control'");
  MatchState reader("plant/cmd", true, &peers);
  EXPECT_EQ(describe_match_problems(peers, {&reader}),
            "DDS: 2 other participant(s) discovered; DDS Security: not authenticated (yet): 'control'; "
            "plant/cmd (reader): no writer matched");
  authenticate(peers, kControl);
  EXPECT_EQ(peers.unauthenticated(), "");
}

// Issue 24, finding 6: the host learns which participants went away, and how (PeerLossSource).
TEST(MatchReport, ParticipantsThatGoAwayAreKeptInOrderWithHowTheyWent) {
  PeerDirectory peers;
  discover(peers, "robodds-control", kControl);
  discover(peers, "robodds-sim", kSim);
  EXPECT_EQ(peers.loss_count(), 0u);
  const std::int64_t before = monotonic_now_ns();
  lose(peers, "robodds-sim", kSim, true);
  lose(peers, "robodds-control", kControl, false);
  ASSERT_EQ(peers.loss_count(), 2u);
  const std::vector<PeerLoss> losses = peers.losses();
  ASSERT_EQ(losses.size(), 2u);
  EXPECT_EQ(losses[0].participant, "robodds-sim");
  EXPECT_TRUE(losses[0].dropped);
  EXPECT_GE(losses[0].at_ns, before);
  EXPECT_EQ(losses[1].participant, "robodds-control");
  EXPECT_FALSE(losses[1].dropped);
  EXPECT_EQ(peers.participants_alive(), 0u);
}

TEST(MatchReport, AnUnsecuredParticipantSaysNothingAboutAuthentication) {
  PeerDirectory peers;
  discover(peers, "robodds-control", kControl);
  EXPECT_EQ(peers.unauthenticated(), "");
}

TEST(MatchReport, AnUnmatchedReaderNamesTheWritersDiscoveredOnItsTopic) {
  PeerDirectory peers;
  discover(peers, "robodds-control", kControl);
  rtps::WriterProxyData writer(4, 4);
  writer.guid(guid_of(1, 0x03));
  writer.topicName("plant/cmd");
  peers.on_publisher_discovery(nullptr, rtps::WriterDiscoveryInfo(writer));
  MatchState reader("plant/cmd", true, &peers);
  EXPECT_EQ(reader.problem(), "plant/cmd (reader): no writer matched (discovered: 'control')");
  MatchState other("plant/state", true, &peers);
  EXPECT_EQ(other.problem(), "plant/state (reader): no writer matched");
}

}  // namespace
}  // namespace robodds
