#pragma once
// syscall(SYS_gettid) answered from a per-thread cache, for the Fast DDS this process links.
//
// Debian's libfastrtps 2.9.1 is built without NDEBUG, so its assertions run: every reliable
// reader's WriterProxy and every writer check `get_mutex_owner() == get_thread_id()`, and
// get_thread_id() is syscall(SYS_gettid). That is ~6 system calls per sample delivered across
// processes (5.2 million in a 1,001-tick run of 200 robots, 44 % of its CPU time in the kernel;
// docs/performance.md, "Across processes at scale"). A thread's id never changes, so this file
// defines `syscall` in the executable: the dynamic linker binds libfastrtps' (and every other
// shared library's) calls of syscall() to it, SYS_gettid is answered from a thread_local and
// every other number is forwarded unchanged to the C library's syscall().
//
// Linked into every program that links robodds_runtime_dds: create_participant() calls
// thread_id_cache_in_use(), which pulls this object file out of the static library.

namespace robodds {

/// True when this process' calls of syscall() from shared libraries (libfastrtps) reach the cache,
/// i.e. the executable exports `syscall` and the dynamic linker resolves it there first.
bool thread_id_cache_in_use();

}  // namespace robodds
