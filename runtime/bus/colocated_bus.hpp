#pragma once
// The bus of a co-located run (`robodds run`, every component in this process), lockstep or real
// time: the components' samples go from writer to readers in memory (MemoryBus: inside write(),
// in write order, as Fast DDS intra-process delivery does) and every sample is also written to
// DDS while a reader there is matched, so `robodds echo/topics`, recorders and other observers on
// the network still see every topic.
//
// Why: through Fast DDS, a sample delivered inside the process went through the writer's and the
// reader's keyed histories, a take, a deserialising copy and several locks: at 200 robots that
// was most of the ~4 us per robot-tick (docs/performance.md, "Cost per robot-tick"). In memory
// it is a callback call. The DDS side keeps its writers (same topics, types, QoS profiles), but
// this process creates no DDS reader: a co-located lockstep run is a closed world, and nothing
// written by another process on the network reaches its components (a stricter rule than the
// real-time and multi-process runs, whose inputs are DDS readers with the sample checks).
//
// Results: the same Inputs, the same lockstep rule, the same samples, so the outputs are
// byte-identical to a run through DDS (tests/integration/determinism_test.sh compares a
// co-located run with one across processes).
//
// Real time (ColocatedWorld::kOpen): the same for every topic a component of this process
// publishes (through DDS each sample cost two keyed histories, a deadline timer re-armed per
// sample on the event thread and a walk of every instance: the cap near 250 robots at 100 Hz,
// docs/performance.md "Real time at scale"); a topic no component here publishes (a producer
// outside the run: another program, `robodds replay`, a Cyclone DDS commander) is read from DDS
// with its sample checks, as before. A writer on the network of a topic produced here reaches
// nothing in this process: the one-producer rule refused its samples anyway (issue 24). Hot
// standby needs DDS ownership and deadlines between processes: such a run keeps the DDS bus.

#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <vector>

#include "runtime/bus/bus.hpp"
#include "runtime/bus/memory_bus.hpp"

namespace robodds {

/// Where the readers of a co-located run take their samples from.
enum class ColocatedWorld {
  kClosed,  ///< lockstep: every reader in memory, nothing from the network
  kOpen,    ///< real time: in memory for the topics produced here, from the network for the others
};

class ColocatedBus : public Bus {
 public:
  /// `network`: the process's DDS bus; it must outlive this bus and every handle made by it.
  /// `produced_here`: the topics a component of this process publishes (kOpen only: with kClosed
  /// every topic is read in memory).
  explicit ColocatedBus(Bus& network, ColocatedWorld world = ColocatedWorld::kClosed,
                        std::set<std::string> produced_here = {});

  /// One writer per (topic, profile), as every Bus: it hands each sample to this process's readers and writes it to `network`.
  std::shared_ptr<WriterHandle> writer(const std::string& topic, const std::string& type_name,
                                       const std::string& profile) override;
  /// An in-memory reader (samples of this process's writers, none from the network), or the
  /// network's reader of a topic not produced here (kOpen).
  std::shared_ptr<ReaderHandle> reader(const std::string& topic, const std::string& type_name,
                                       const std::string& profile, SampleCallback on_sample,
                                       ReaderEventCallback on_event) override;
  /// As reader(); the key filter applies to the network's readers (in memory every writer is ours).
  std::shared_ptr<ReaderHandle> filtered_reader(const std::string& topic, const std::string& type_name,
                                                const std::string& profile, SampleCallback on_sample,
                                                ReaderEventCallback on_event, KeyFilter filter) override;
  /// The DDS writers' flush (observers' reliable readers); the in-memory part has nothing pending.
  void flush(std::chrono::milliseconds timeout) override;
  /// An in-memory writer's name, else the network's name of a DDS writer (kOpen).
  std::string writer_name(std::uint64_t writer_id) const override;
  /// In memory every writer is this process's; a DDS writer as the network knows it.
  bool writer_runs_any(std::uint64_t writer_id, const std::vector<std::string>& components) const override;
  /// What the network's readers (kOpen) dropped undecoded.
  std::map<std::string, std::uint64_t> undecodable_samples() const override;

 private:
  /// Whether the readers of `topic` are the network's.
  bool reads_network(const std::string& topic) const;

  Bus& network_;
  ColocatedWorld world_;
  std::set<std::string> produced_here_;
  MemoryBus local_;
  std::mutex mutex_;
  std::map<std::string, std::shared_ptr<WriterHandle>> writers_;  // by "topic|profile": one per process
};

}  // namespace robodds
