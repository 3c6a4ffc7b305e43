#include "runtime/base/realtime_priority.hpp"

#include <gtest/gtest.h>

#include <sched.h>

#include <cerrno>

#include "runtime/base/error.hpp"

namespace robodds {
namespace {

TEST(RtPriority, AcceptsOneTo99) {
  EXPECT_EQ(rt_priority_problem("1"), "");
  EXPECT_EQ(rt_priority_problem("50"), "");
  EXPECT_EQ(rt_priority_problem("99"), "");
  EXPECT_EQ(rt_priority_from_text("50"), 50);
}

TEST(RtPriority, RefusesEverythingElseNamingTheOption) {
  for (const char* bad : {"0", "100", "-1", "+5", "5.0", "nan", "", " 5", "50x", "99999999999999999999"}) {
    EXPECT_NE(rt_priority_problem(bad), "") << bad;
    EXPECT_THROW(rt_priority_from_text(bad), ConfigError) << bad;
  }
  try {
    rt_priority_from_text("0");
    ADD_FAILURE() << "0 was accepted";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()), "--rt-priority 0: must be a whole number 1..99 (the SCHED_FIFO priority; 99 is the highest)");
  }
}

TEST(RtPriority, CommunicationThreadsOneBelowTheLoop) {
  EXPECT_EQ(communication_priority(50), 49);
  EXPECT_EQ(communication_priority(99), 98);
  EXPECT_EQ(communication_priority(2), 1);
  EXPECT_EQ(communication_priority(1), 1);  // nothing lower for SCHED_FIFO
}

TEST(RtPriority, RaisingTheLoopWithoutAnAppliedPriorityChangesNothing) {
  const int policy = sched_getscheduler(0);
  raise_loop_thread();
  EXPECT_EQ(sched_getscheduler(0), policy);
}

TEST(RtPriority, ApplyRefusesAPriorityOutOfRangeBeforeTouchingTheScheduler) {
  const int policy = sched_getscheduler(0);
  EXPECT_THROW(apply_rt_priority(0), ConfigError);
  EXPECT_THROW(apply_rt_priority(100), ConfigError);
  EXPECT_EQ(sched_getscheduler(0), policy);
}

TEST(RtPriority, SchedRefusalSaysWhyAndWhatToDo) {
  RtPermissions none;
  none.rtprio_limit = 0;
  EXPECT_EQ(sched_refusal(50, EPERM, none),
            "--rt-priority 50: SCHED_FIFO refused (no CAP_SYS_NICE and RLIMIT_RTPRIO 0): run as root, give the capability "
            "(setcap cap_sys_nice,cap_ipc_lock+ep; docker: cap_add SYS_NICE), or raise rtprio to at least 50 in "
            "/etc/security/limits.conf");
  RtPermissions capable;
  capable.cap_sys_nice = true;
  const std::string cgroup = sched_refusal(10, EPERM, capable);
  EXPECT_NE(cgroup.find("although CAP_SYS_NICE is held"), std::string::npos) << cgroup;
  EXPECT_NE(cgroup.find("cpu.rt_runtime_us"), std::string::npos) << cgroup;
}

TEST(RtPriority, MlockRefusalNamesTheLimit) {
  RtPermissions limited;
  limited.memlock_limit = 8388608;
  const std::string text = mlock_refusal(50, ENOMEM, limited);
  EXPECT_EQ(text.rfind("--rt-priority 50: locking the memory (mlockall) refused (", 0), 0u) << text;
  EXPECT_NE(text.find("no CAP_IPC_LOCK and RLIMIT_MEMLOCK 8388608 bytes"), std::string::npos) << text;
  EXPECT_NE(text.find("memlock unlimited"), std::string::npos) << text;
  RtPermissions unlimited;
  unlimited.cap_ipc_lock = true;
  EXPECT_EQ(mlock_refusal(1, ENOMEM, unlimited).find("RLIMIT_MEMLOCK"), std::string::npos);
}

}  // namespace
}  // namespace robodds
