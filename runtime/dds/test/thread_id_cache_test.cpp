#include "runtime/dds/thread_id_cache.hpp"

#include <gtest/gtest.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <string>
#include <thread>

namespace robodds {
namespace {

// The kernel's answer, never through syscall(): glibc's gettid() makes the system call itself.
long kernel_thread_id() { return static_cast<long>(::gettid()); }

TEST(ThreadIdCache, SharedLibrariesCallsOfSyscallReachTheCache) {
  // Fails when the executable does not export syscall (then libfastrtps' calls go to libc).
  EXPECT_TRUE(thread_id_cache_in_use());
}

TEST(ThreadIdCache, AnswersEachThreadItsOwnId) {
  EXPECT_EQ(syscall(SYS_gettid), kernel_thread_id());
  EXPECT_EQ(syscall(SYS_gettid), kernel_thread_id());  // from the cache now
  long in_other_thread = 0;
  long kernel_in_other_thread = 0;
  std::thread other([&] {
    in_other_thread = syscall(SYS_gettid);
    kernel_in_other_thread = kernel_thread_id();
  });
  other.join();
  EXPECT_EQ(in_other_thread, kernel_in_other_thread);
  EXPECT_NE(in_other_thread, syscall(SYS_gettid));
}

TEST(ThreadIdCache, AForkedChildGetsItsOwnId) {
  ASSERT_EQ(syscall(SYS_gettid), kernel_thread_id());  // the parent's id is cached
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    _exit(syscall(SYS_gettid) == kernel_thread_id() && syscall(SYS_gettid) == getpid() ? 0 : 1);
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0) << "the child answered its parent's thread id";
}

TEST(ThreadIdCache, ForwardsEveryOtherSystemCallWithItsArgumentsAndErrno) {
  EXPECT_EQ(syscall(SYS_getpid), getpid());
  errno = 0;
  EXPECT_EQ(syscall(SYS_close, -1), -1);
  EXPECT_EQ(errno, EBADF);
  // Six arguments reach the kernel: pipe2 with flags, then write and read through the pipe.
  int fds[2] = {-1, -1};
  ASSERT_EQ(syscall(SYS_pipe2, fds, 0), 0);
  const char sent[3] = {'a', 'b', 'c'};
  EXPECT_EQ(syscall(SYS_write, fds[1], sent, sizeof(sent)), 3);
  char received[3] = {};
  EXPECT_EQ(syscall(SYS_read, fds[0], received, sizeof(received)), 3);
  EXPECT_EQ(std::string(received, 3), "abc");
  close(fds[0]);
  close(fds[1]);
}

}  // namespace
}  // namespace robodds
