#!/usr/bin/env python3
"""freeze_thread.py PID SECONDS: stops one thread of a live process (the thread PID itself: a
process's main thread, which runs a robodds host's loop) for SECONDS, leaving its other threads
(Fast DDS's receive, event and announcement threads) running: a hung loop in a live process, as a
component's step that never returns would make it. Uses ptrace (PTRACE_SEIZE + PTRACE_INTERRUPT
stop that one task); the thread resumes when this script ends (the kernel detaches it). Needs
CAP_SYS_PTRACE (root) or ptrace_scope 0 and the same user. Prints "frozen <epoch s>" once the
thread is stopped."""
import ctypes
import os
import sys
import time

PTRACE_SEIZE = 0x4206
PTRACE_INTERRUPT = 0x4207

libc = ctypes.CDLL(None, use_errno=True)
libc.ptrace.argtypes = [ctypes.c_long, ctypes.c_long, ctypes.c_void_p, ctypes.c_void_p]
tid, seconds = int(sys.argv[1]), float(sys.argv[2])
for request in (PTRACE_SEIZE, PTRACE_INTERRUPT):
    if libc.ptrace(request, tid, None, None) != 0:
        sys.exit(f"freeze_thread: ptrace({hex(request)}, {tid}) failed: {os.strerror(ctypes.get_errno())}")
# Wait until the thread is really stopped ("t (tracing stop)" in its status).
deadline = time.time() + 5.0
while "t (tracing stop)" not in open(f"/proc/{tid}/task/{tid}/status").read():
    if time.time() > deadline:
        sys.exit(f"freeze_thread: thread {tid} did not stop within 5 s")
    time.sleep(0.01)
print(f"frozen {time.time():.3f}", flush=True)
time.sleep(seconds)
