#include "runtime/dds/thread_id_cache.hpp"

#include <dlfcn.h>
#include <pthread.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cstdarg>

namespace {

// 0: not asked yet in this thread. A tid is never 0 (that is the idle task's pid).
thread_local long cached_thread_id = 0;

using SyscallFunction = long (*)(long, ...);

// The C library's syscall(): the next definition after this executable's own.
SyscallFunction libc_syscall() {
  static const SyscallFunction function = reinterpret_cast<SyscallFunction>(dlsym(RTLD_NEXT, "syscall"));
  return function;
}

// fork(): the child's only thread has a new id, and it inherits the parent thread's cache.
void forget_thread_id_in_child() { cached_thread_id = 0; }

const int registered_at_fork = pthread_atfork(nullptr, nullptr, forget_thread_id_in_child);

}  // namespace

extern "C" long syscall(long number, ...) {
  if (number == SYS_gettid) {
    if (cached_thread_id == 0) {
      cached_thread_id = libc_syscall()(SYS_gettid);
    }
    return cached_thread_id;
  }
  // syscall(2) passes at most six arguments in registers. Reading all six, as the C library's own
  // syscall() loads all six registers, forwards any call unchanged (the unused ones are ignored).
  va_list arguments;
  va_start(arguments, number);
  long a[6];
  for (long& argument : a) {
    argument = va_arg(arguments, long);
  }
  va_end(arguments);
  return libc_syscall()(number, a[0], a[1], a[2], a[3], a[4], a[5]);
}

namespace robodds {

bool thread_id_cache_in_use() {
  // What a shared library's call of syscall() is bound to: the first definition in the global scope.
  const void* bound = dlsym(RTLD_DEFAULT, "syscall");
  return registered_at_fork == 0 && bound == reinterpret_cast<const void*>(&::syscall);
}

}  // namespace robodds
