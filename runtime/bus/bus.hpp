#pragma once
// The runtime's view of DDS, free of Fast DDS headers: typed I/O (io.hpp) and the host talk
// to these interfaces; runtime/dds/dds_bus.cpp implements them with Fast DDS. Samples cross this
// boundary as `const void*` pointing at the generated C++ type named by `type_name`.

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "runtime/bus/step_needs.hpp"
#include "runtime/bus/run_digest.hpp"

namespace robodds {

enum class TimeMode { kLockstep, kRealtime };

class WriterHandle {
 public:
  virtual ~WriterHandle() = default;
  virtual void write(const void* sample) = 0;
  virtual const std::string& topic() const = 0;
  /// Waits until every reader matched now has acknowledged all this writer wrote: true, or false
  /// after `timeout`. A process that exits right after a write calls it first, or the sample can
  /// be lost with it (Fast DDS drops a sample it has not yet handed out when its writer leaves).
  /// In-process delivery completes inside write(): nothing to wait for.
  virtual bool wait_acknowledged(std::chrono::milliseconds /*timeout*/) { return true; }
  /// False when no reader is matched now, so a volatile sample written now reaches nobody (a
  /// reader matched later gets only later samples either way). Default: true (unknown).
  virtual bool has_matched_readers() const { return true; }
  /// This writer will not write the instance of `sample` (its key members; the rest is ignored)
  /// again: the transport may forget what it keeps of it. Fast DDS unregisters the instance, and
  /// once every matched reader has acknowledged it the instance's samples leave the writer
  /// history. Without that, one ended instance's samples stay the oldest in a keyed history for
  /// good, and a reliable writer announces every later sample of other instances as a hole after
  /// them (GAP), at a cost per heartbeat that grows with the run (docs/deployment.md, "Long runs
  /// and failures across machines"). A reader that matches later does not get the ended
  /// instance's last sample; a later write() of the same key starts the instance again.
  /// Default: nothing kept (in-memory delivery).
  virtual void end_instance(const void* /*sample*/) {}
};

/// What the transport knows about a sample besides its contents: who wrote it (to tell two
/// producers of one instance apart and to name a hostile writer) and when this process received
/// it (to judge freshness by the receiver's own clock, never only by the sender's stamp).
struct SampleMeta {
  /// The writing endpoint, stable for the writer's life: a hash of the DDS writer GUID (Fast DDS)
  /// or a per-writer number (MemoryBus). 0: unknown. Bus::writer_name() spells it.
  std::uint64_t writer_id = 0;
  /// steady_clock (CLOCK_MONOTONIC) time at which this process took the sample, ns since the
  /// clock's epoch. 0: unknown (e.g. a unit test feeding an Input directly).
  std::int64_t received_ns = 0;
  /// One delivery of a sample to several readers in this process (MemoryBus: every reader inside
  /// write(), one after the other on one thread) points all of them at one flag: the first reader
  /// whose content checks pass it sets it, and the others do not check the same bytes again
  /// (lockstep only: there the checks depend on the sample alone). nullptr: no sharing (DDS).
  bool* checks_passed = nullptr;
};

/// steady_clock now in ns: the clock of SampleMeta::received_ns.
inline std::int64_t monotonic_now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// This process's wall clock (system_clock) in ns since the Unix epoch: the clock of real-time
/// stamps (SampleHeader::stamp_ns) and of a real-time run's epoch.
inline std::int64_t wall_clock_now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch()).count();
}

/// Called for each valid sample, on a DDS thread or, for a writer in the same process, inside
/// that writer's write(): it must only store the sample and return.
using SampleCallback = std::function<void(const void* sample, const SampleMeta& meta)>;
/// Called for QoS events on a reader (deadline missed, liveliness lost, incompatible QoS).
using ReaderEventCallback = std::function<void(const std::string& event)>;

class ReaderHandle {
 public:
  virtual ~ReaderHandle() = default;
  /// This subscriber reads only the samples `needs` names (lockstep, newest-only reads): the bus
  /// may leave the others out once every subscriber of its reader said so. Call before
  /// Bus::start(). Default: every sample is delivered.
  virtual void set_step_needs(const StepNeeds& /*needs*/) {}
};

/// Which instance keys a subscriber takes (e.g. those of a scenario's robots), so that a
/// transport can drop a sample of any other key before it keeps anything for that key (Fast DDS:
/// an instance in the reader's history, with a deadline timer, for good): a flood of keys must
/// cost nothing to keep (docs/security.md, "Floods").
struct KeyFilter {
  /// Whether the subscriber takes instance key `key` (the sample's 64-bit instance key).
  std::function<bool(std::uint64_t key)> takes;
  /// The transport dropped a sample of `key` from writer `writer_id` (SampleMeta::writer_id)
  /// because no subscriber of its reader takes that key: count it as the subscriber would.
  std::function<void(std::uint64_t key, std::uint64_t writer_id)> refused;
};

class Bus {
 public:
  virtual ~Bus() = default;
  /// One writer per (topic, profile) per process: repeated calls return the same writer.
  virtual std::shared_ptr<WriterHandle> writer(const std::string& topic, const std::string& type_name,
                                               const std::string& profile) = 0;
  /// One DDS reader per (topic, profile) per process; each call adds a callback to it.
  virtual std::shared_ptr<ReaderHandle> reader(const std::string& topic, const std::string& type_name,
                                               const std::string& profile, SampleCallback on_sample,
                                               ReaderEventCallback on_event) = 0;
  /// reader() for a subscriber that takes only the keys `filter` takes. A sample whose key no
  /// subscriber of the reader takes may be dropped before the transport keeps any state for it;
  /// then each subscriber's `refused` is called instead of its `on_sample`. A subscriber added
  /// with reader() takes every key. Default: reader() (a bus that keeps no per-key state, e.g.
  /// MemoryBus: the subscriber's own check refuses such samples).
  virtual std::shared_ptr<ReaderHandle> filtered_reader(const std::string& topic, const std::string& type_name,
                                                        const std::string& profile, SampleCallback on_sample,
                                                        ReaderEventCallback on_event, KeyFilter /*filter*/) {
    return reader(topic, type_name, profile, std::move(on_sample), std::move(on_event));
  }
  /// Waits until every reliable writer's samples are acknowledged (before a process exits).
  virtual void flush(std::chrono::milliseconds timeout) = 0;
  /// Between begin_write_batch() and end_write_batch() (nestable, per thread) the samples the
  /// calling thread writes may be held and leave together at the outermost end, one network
  /// message per destination instead of one per sample. Nothing written in between reaches another
  /// process before the end: never wait for a peer inside. Default: nothing is held.
  virtual void begin_write_batch() {}
  virtual void end_write_batch() {}
  /// begin_write_batch() for the lifetime of a scope, end_write_batch() however it is left.
  class WriteBatch {
   public:
    explicit WriteBatch(Bus& bus) : bus_(bus) { bus_.begin_write_batch(); }
    ~WriteBatch() { bus_.end_write_batch(); }
    WriteBatch(const WriteBatch&) = delete;
    WriteBatch& operator=(const WriteBatch&) = delete;

   private:
    Bus& bus_;
  };
  /// One line naming this process's topics without a matched peer and any incompatible QoS
  /// (both sides' policies), appended to lockstep timeout errors; empty when all matched.
  virtual std::string match_report() { return {}; }
  /// Names the writer of SampleMeta::writer_id for log lines and errors, e.g.
  /// "'control' (writer 01.0f...|0.0.3.3)"; "writer <id>" when the bus knows nothing more.
  virtual std::string writer_name(std::uint64_t writer_id) const { return "writer " + std::to_string(writer_id); }
  /// Whether the process of writer `writer_id` runs one of `components` (scenario component
  /// names), as our hosts announce it (docs/architecture.md, "One producer per instance"): false
  /// for a writer that announces nothing (a foreign program) or other components. The in-memory
  /// buses are closed worlds whose every writer is this process's: true.
  virtual bool writer_runs_any(std::uint64_t /*writer_id*/, const std::vector<std::string>& /*components*/) const {
    return true;
  }
  /// Hot standby: this process's readers and writers of `topic` created after this call request
  /// DDS EXCLUSIVE ownership, its writers with `writer_strength` (the highest alive strength owns
  /// each instance). Default: nothing (a bus without ownership, e.g. MemoryBus).
  virtual void set_exclusive_ownership(const std::string& /*topic*/, std::uint32_t /*writer_strength*/) {}
  /// How many robots this process's components serve. A bus whose writers keep a deep per-instance history may spread
  /// a robot-keyed topic's instances over several writers of that topic
  /// (runtime/bus/instance_spread.hpp); readers see no difference but the writer GUIDs. Call before
  /// the first writer() call. Default: nothing.
  virtual void expect_robots(std::size_t /*robots*/) {}
  /// KEEP_LAST depth of a writer with QoS profile `profile` (samples kept per instance), or
  /// nullopt when the bus keeps no such history (KEEP_ALL, or a bus without one, e.g. MemoryBus).
  virtual std::optional<std::size_t> writer_history_depth(const std::string& /*profile*/) const { return std::nullopt; }
  /// Samples of this process's input topics that the DDS type support could not decode and
  /// dropped (runtime/dds/undecodable.hpp), per topic; topics with none are left out. Default:
  /// none (a bus without decoding, e.g. MemoryBus). summary.json "hosts".<member>."undecodable".
  virtual std::map<std::string, std::uint64_t> undecodable_samples() const { return {}; }
  /// The names of the DDS participants this process has discovered so far (PeerWatch), or
  /// nullopt for a bus that discovers nothing (MemoryBus, a co-located run's in-memory bus).
  virtual std::optional<std::vector<std::string>> discovered_participants() const { return std::nullopt; }
  /// The hosts of run `run_id` discovered so far (also those gone since) that announced what they loaded
  /// (run_digest.hpp). Default: none (a bus that discovers nothing).
  virtual std::vector<PeerDigest> peer_digests(std::uint64_t /*run_id*/) const { return {}; }
  /// Grows whenever discovery learns or loses a participant: peer_digests() and
  /// discovered_participants() need to be asked again only then. Default: never.
  virtual std::uint64_t discovery_generation() const { return 0; }
};

}  // namespace robodds
