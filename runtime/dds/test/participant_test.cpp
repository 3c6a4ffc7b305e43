// ParticipantPtr: a participant is deleted the complete way whatever unwinds past it.
// Real Fast DDS participants on domain 59 (the domain of this step's tests, tests/CMakeLists.txt);
// nothing is published.

#include "runtime/dds/participant.hpp"

#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>

namespace robodds {
namespace {
namespace dds = eprosima::fastdds::dds;

constexpr int kDomain = 59;

TEST(ParticipantPtr, AThrowAfterCreationDeletesTheEntitiesAndTheParticipant) {
  auto listener = std::make_unique<dds::DomainParticipantListener>();  // outlives the participant
  auto build_then_throw = [&] {
    ParticipantPtr participant =
        create_participant(kDomain, dds::PARTICIPANT_QOS_DEFAULT, listener.get(), dds::StatusMask::none(), "default");
    ASSERT_NE(participant->create_publisher(dds::PUBLISHER_QOS_DEFAULT), nullptr);
    ASSERT_NE(participant->create_subscriber(dds::SUBSCRIBER_QOS_DEFAULT), nullptr);
    ASSERT_EQ(dds::DomainParticipantFactory::get_instance()->lookup_participant(kDomain), participant.get());
    throw std::runtime_error("failed after the participant was created");
  };
  EXPECT_THROW(build_then_throw(), std::runtime_error);
  // delete_participant() refuses a participant that still contains entities: gone means both done.
  EXPECT_EQ(dds::DomainParticipantFactory::get_instance()->lookup_participant(kDomain), nullptr);
}

// exit_now_if_dds_is_closed() ends the process early only when this count says that every
// participant is deleted: it must follow creation and deletion exactly.
TEST(ParticipantPtr, LiveParticipantsCountsCreationAndDeletion) {
  const int before = live_participants();
  {
    ParticipantPtr participant =
        create_participant(kDomain, dds::PARTICIPANT_QOS_DEFAULT, nullptr, dds::StatusMask::none(), "default");
    EXPECT_EQ(live_participants(), before + 1);
    ParticipantPtr second =
        create_participant(kDomain, dds::PARTICIPANT_QOS_DEFAULT, nullptr, dds::StatusMask::none(), "default");
    EXPECT_EQ(live_participants(), before + 2);
  }
  EXPECT_EQ(live_participants(), before);
}

}  // namespace
}  // namespace robodds
