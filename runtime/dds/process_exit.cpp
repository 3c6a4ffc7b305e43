#include "runtime/dds/process_exit.hpp"

#include <fastdds/dds/log/Log.hpp>

#include <cstdio>
#include <cstdlib>

#include "runtime/dds/participant.hpp"

namespace robodds {

int exit_now_if_dds_is_closed(int code) {
  if (live_participants() != 0) {
    return code;
  }
  eprosima::fastdds::dds::Log::Flush();  // returns at once when Fast DDS never logged
  std::fflush(nullptr);
  std::_Exit(code);
}

}  // namespace robodds
