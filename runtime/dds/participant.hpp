#pragma once
// Owning a DomainParticipant (runtime-internal; includes Fast DDS): whatever happens after it is
// created, including an exception, it is deleted the complete way before what it points to dies.

#include <fastdds/dds/core/status/StatusMask.hpp>
#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantListener.hpp>
#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>

#include <memory>
#include <string>

namespace robodds {

/// Detaches the participant's listener, deletes every entity it contains (their listeners are
/// called no more), then deletes it through the factory, which also releases its shared memory.
struct ParticipantDeleter {
  void operator()(eprosima::fastdds::dds::DomainParticipant* participant) const;
};

/// A participant deleted by ParticipantDeleter. Declare it AFTER every member its listeners and its
/// entities' listeners point to: members die in reverse order, also when a constructor throws.
using ParticipantPtr = std::unique_ptr<eprosima::fastdds::dds::DomainParticipant, ParticipantDeleter>;

/// Creates a participant on `domain_id`; RunError naming the domain and `profile` if Fast DDS refuses.
ParticipantPtr create_participant(int domain_id, const eprosima::fastdds::dds::DomainParticipantQos& qos,
                                  eprosima::fastdds::dds::DomainParticipantListener* listener,
                                  const eprosima::fastdds::dds::StatusMask& mask, const std::string& profile);

/// How many participants create_participant() made that are not deleted yet.
int live_participants();

}  // namespace robodds
