#pragma once
// The bus of a co-located lockstep run (`robodds run`, every component in this process): the
// components' samples go from writer to readers in memory (MemoryBus: inside write(), in write
// order, as Fast DDS intra-process delivery does) and every sample is also written to DDS, so
// `robodds echo/topics`, recorders and other observers on the network still see every topic.
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

#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "runtime/bus/bus.hpp"
#include "runtime/bus/memory_bus.hpp"

namespace robodds {

class ColocatedBus : public Bus {
 public:
  /// `network`: the process's DDS bus; it must outlive this bus and every handle made by it.
  explicit ColocatedBus(Bus& network);

  /// One writer per (topic, profile), as every Bus: it hands each sample to this process's readers and writes it to `network`.
  std::shared_ptr<WriterHandle> writer(const std::string& topic, const std::string& type_name,
                                       const std::string& profile) override;
  /// An in-memory reader only: samples of this process's writers, none from the network.
  std::shared_ptr<ReaderHandle> reader(const std::string& topic, const std::string& type_name,
                                       const std::string& profile, SampleCallback on_sample,
                                       ReaderEventCallback on_event) override;
  /// The DDS writers' flush (observers' reliable readers); the in-memory part has nothing pending.
  void flush(std::chrono::milliseconds timeout) override;
  std::string writer_name(std::uint64_t writer_id) const override;

 private:
  Bus& network_;
  MemoryBus local_;
  std::mutex mutex_;
  std::map<std::string, std::shared_ptr<WriterHandle>> writers_;  // by "topic|profile": one per process
};

}  // namespace robodds
