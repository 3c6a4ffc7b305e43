#pragma once
// Ending a robodds process without Fast DDS's teardown at exit. This header stays free of Fast DDS
// includes.

namespace robodds {

/// Ends the process with `code` at once when every participant this process created is deleted:
/// flushes Fast DDS's log, stdout and stderr, then std::_Exit(), skipping the static destructors.
/// Fast DDS 2.9's DomainParticipantFactory destructor, one of them, deletes the participants left
/// (none here) and then sleeps 100 ms unconditionally: a tenth of a second on every robodds
/// process, ~1 % of the paper-2 run. With a participant still alive it returns `code`, and the
/// normal exit deletes that participant.
int exit_now_if_dds_is_closed(int code);

}  // namespace robodds
