#pragma once
// How large a lockstep host's shared-memory segment must be (no Fast DDS here: a number of bytes
// for DdsOptions::shm_segment_bytes).

#include <cstddef>
#include <cstdint>

namespace robodds {

/// Bytes budgeted per robot a host serves and per tick it may run ahead of a reader: what a host
/// of one robot-keyed output per robot (a plant: one ~230-byte RobotState RTPS message per robot
/// and step) writes, twice over.
inline constexpr std::size_t kShmBytesPerRobotTick = 512;
/// Never more than this (the segment is written out in /dev/shm when the participant starts).
inline constexpr std::size_t kShmSegmentMaxBytes = std::size_t{64} << 20;

/// The shared-memory segment a lockstep host across processes needs, in bytes; 0 when the
/// profile's own (Fast DDS: 512 KiB) is enough. Why: a process's outgoing shared-memory messages
/// live in its own segment until every receiving process has handled them, and Fast DDS 2.9.1
/// frees them oldest first. With `--lockstep-window W` a host may write W ticks before the slowest
/// reader of its samples catches up, so the segment holds up to (W + 1) ticks of its output; when
/// a message does not fit, Fast DDS drops it without a word (SharedMemManager::alloc_buffer
/// "allocation overflow", logged at info level only) and the reliable protocol repairs it a
/// heartbeat later: with 200 robots and W = 16 the 512 KiB default overflowed every few steps and
/// the run fell from ~550 to ~200 ticks/s (docs/performance.md, "Shared-memory segment").
/// `robots_served`: robots whose instances this host's components write (Scenario::robots_served_by).
std::size_t shm_segment_bytes(std::size_t robots_served, std::size_t lockstep_window);

}  // namespace robodds
