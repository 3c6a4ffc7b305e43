#pragma once
// How much a lockstep host's transports must hold for its window (no Fast DDS here: a number of
// bytes for DdsOptions::transport_buffer_bytes).

#include <cstddef>
#include <cstdint>

namespace robodds {

/// Bytes budgeted per robot a host serves and per tick it may be ahead of (or behind) its peers:
/// what a host of one robot-keyed output per robot (a plant: one ~230-byte RobotState RTPS
/// message per robot and step) writes, or an evaluator of 1.6 samples per robot and step reads,
/// with room to spare.
inline constexpr std::size_t kTransportBytesPerRobotTick = 512;
/// Never more than this (a segment is written out in /dev/shm when the participant starts).
inline constexpr std::size_t kTransportBufferMaxBytes = std::size_t{64} << 20;

/// The bytes a lockstep host across processes needs in its shared-memory segment and in its UDP
/// receive buffers; 0 up to Fast DDS' default 512 KiB segment (the profile's own segment and the
/// kernel's default receive buffer, 208 KiB on Debian, then stay: a strict run of up to 512
/// robots changes nothing). Why: with `--lockstep-window W` a host may
/// write W ticks before the slowest reader of its samples catches up, and may receive W ticks of
/// its peers' samples before its own receive thread catches up, so each side holds up to (W + 1)
/// ticks of traffic. What does not fit is dropped without a word (Fast DDS 2.9.1's shared memory:
/// SharedMemManager::alloc_buffer "allocation overflow", logged at info level; UDP: the kernel,
/// when the socket's receive buffer is full) and the reliable protocol repairs it a heartbeat
/// later: with 200 robots and W = 16 the run fell from ~550-600 to ~200 ticks/s over shared memory
/// and to ~80 over UDP (docs/performance.md, "Session 15").
/// `robots_served`: robots whose instances this host's components handle (Scenario::robots_served_by).
std::size_t transport_buffer_bytes(std::size_t robots_served, std::size_t lockstep_window);

}  // namespace robodds
