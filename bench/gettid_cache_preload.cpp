// DIAGNOSTIC ONLY (bench/run_benchmarks.sh, docs/performance.md), never part of a deployment.
//
// The Debian libfastrtps 2.9.1 is built without NDEBUG, so its asserts stay in: every
// WriterProxy call checks `get_mutex_owner() == get_thread_id()`, and get_thread_id() is
// syscall(__NR_gettid), i.e. several system calls per delivered sample. Loaded with
//   LD_PRELOAD=<build>/bench/libgettid_cache_preload.so <program>
// this library answers syscall(SYS_gettid) from a per-thread cache and forwards every other
// syscall() unchanged, which estimates what the same code costs with a Fast DDS built with
// NDEBUG (Release). glibc's own system calls do not go through syscall() and are unaffected.
#include <dlfcn.h>
#include <pthread.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cstdarg>

namespace {

thread_local long cached_tid = 0;

using SyscallFn = long (*)(long, ...);

SyscallFn real_syscall() {
  static const SyscallFn fn = reinterpret_cast<SyscallFn>(dlsym(RTLD_NEXT, "syscall"));
  return fn;
}

void forget_tid_in_child() { cached_tid = 0; }  // fork(): the child's thread has a new id

struct Init {
  Init() { pthread_atfork(nullptr, nullptr, forget_tid_in_child); }
} init;

}  // namespace

extern "C" long syscall(long number, ...) {
  if (number == SYS_gettid) {
    if (cached_tid == 0) {
      cached_tid = real_syscall()(SYS_gettid);
    }
    return cached_tid;
  }
  // syscall(2) takes at most six arguments; reading unused ones is harmless on x86-64/arm64.
  va_list ap;
  va_start(ap, number);
  long a[6];
  for (long& x : a) {
    x = va_arg(ap, long);
  }
  va_end(ap);
  return real_syscall()(number, a[0], a[1], a[2], a[3], a[4], a[5]);
}
