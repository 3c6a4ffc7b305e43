#include "runtime/dds/participant.hpp"

#include <fastdds/dds/domain/DomainParticipantFactory.hpp>

#include <atomic>

#include "runtime/dds/qos_files.hpp"
#include "runtime/dds/send_batch.hpp"
#include "runtime/dds/thread_id_cache.hpp"
#include "runtime/base/error.hpp"
#include "runtime/base/log.hpp"
#include "runtime/health/shutdown_watchdog.hpp"

namespace robodds {
namespace dds = eprosima::fastdds::dds;
using eprosima::fastrtps::types::ReturnCode_t;

namespace {

std::atomic<int> g_live_participants{0};

}  // namespace

int live_participants() { return g_live_participants.load(); }

void ParticipantDeleter::operator()(dds::DomainParticipant* participant) const {
  if (participant == nullptr) {
    return;
  }
  const std::string name = participant->get_qos().name().to_string();
  // Fast DDS waits here for its event/receive threads and locks without a timeout of its own.
  ShutdownWatchdog watchdog("deleting DDS participant '" + name + "' and its writers and readers");
  participant->set_listener(nullptr);
  if (participant->delete_contained_entities() != ReturnCode_t::RETCODE_OK) {
    log::warn("dds", "could not delete the entities of participant " + name);
  }
  if (dds::DomainParticipantFactory::get_instance()->delete_participant(participant) != ReturnCode_t::RETCODE_OK) {
    log::warn("dds", "could not delete participant " + name);
    return;  // still alive: the factory deletes it at exit
  }
  --g_live_participants;
  const SendBatchCounters batches = send_batch_counters();
  if (batches.batches_sent > 0 || batches.malformed_received > 0) {
    log::debug("dds", "send batches so far in this process: " + std::to_string(batches.batches_sent) + " sent with " +
                          std::to_string(batches.messages_batched) + " RTPS messages, " +
                          std::to_string(batches.messages_not_held) + " messages sent at once inside batches, " +
                          std::to_string(batches.malformed_received) + " malformed received");
  }
}

ParticipantPtr create_participant(int domain_id, const dds::DomainParticipantQos& qos, dds::DomainParticipantListener* listener,
                                  const dds::StatusMask& mask, const std::string& profile) {
  // Once per process: whether Fast DDS' assertions get their thread ids without a system call.
  static const bool thread_id_cache_logged = [] {
    log::debug("dds", thread_id_cache_in_use() ? "syscall(SYS_gettid) answered from the per-thread cache"
                                               : "syscall(SYS_gettid) NOT cached: the executable does not export syscall()");
    return true;
  }();
  (void)thread_id_cache_logged;
  take_dds_errors();  // only this creation's
  // Its shared-memory and UDPv4 transports batch what a thread sends inside open_send_batch() (send_batch.hpp).
  dds::DomainParticipantQos batching = qos;
  batching.transport().user_transports = batching_transports(qos.transport().user_transports);
  ParticipantPtr participant(dds::DomainParticipantFactory::get_instance()->create_participant(domain_id, batching, listener, mask));
  if (participant == nullptr) {
    const std::string reasons = take_dds_errors();
    throw RunError("could not create a DDS participant on domain " + std::to_string(domain_id) + " with profile '" +
                   profile + "'" + (reasons.empty() ? std::string() : ": Fast DDS: " + reasons));
  }
  ++g_live_participants;
  return participant;
}

}  // namespace robodds
