#pragma once
// An in-memory Bus for unit tests of components and of the host loop: no Fast DDS, no
// network, no discovery. It keeps the delivery rules the lockstep contract relies on
// (docs/architecture.md, "Determinism"):
// - write() hands the sample to every reader callback of the topic before it returns, like
//   Fast DDS intra-process delivery, in write order. A write made by a callback (or by
//   anything it calls) is queued and delivered, still inside the outermost write(), after the
//   current sample has reached every callback: every reader sees the same order.
// - No lock is held while a callback runs, so a callback may write, subscribe or advertise.
// - One writer per (topic, profile); one reader per (topic, profile) with several callbacks.
// - Writers with the transient-local `mission` profile keep the newest sample of each
//   instance (idl::instance_key); a callback added later on a `mission` reader gets them at
//   once, in key order. Every other profile is volatile: a late reader gets nothing old.
// Safe to call from any thread; the one-order guarantee is per writing thread (in the tests the
// host's executor thread does all the writing).

#include <memory>
#include <string>

#include "runtime/bus/bus.hpp"

namespace robodds {

class MemoryBus : public Bus {
 public:
  MemoryBus();
  ~MemoryBus() override;
  MemoryBus(const MemoryBus&) = delete;
  MemoryBus& operator=(const MemoryBus&) = delete;

  /// ConfigError if `type_name` is not an IDL topic type.
  std::shared_ptr<WriterHandle> writer(const std::string& topic, const std::string& type_name,
                                       const std::string& profile) override;
  /// ConfigError if `type_name` is not an IDL topic type or differs from the topic's earlier
  /// type. Destroying the returned handle removes the callback.
  std::shared_ptr<ReaderHandle> reader(const std::string& topic, const std::string& type_name,
                                       const std::string& profile, SampleCallback on_sample,
                                       ReaderEventCallback on_event) override;
  /// Nothing to acknowledge: delivery is complete when write() returns.
  void flush(std::chrono::milliseconds timeout) override;
  /// "in-memory writer 3 (sim/clock|<profile>)": every writer handle is one writer id.
  std::string writer_name(std::uint64_t writer_id) const override;
  /// Whether `writer_id` is one of this bus's writers (SampleMeta::writer_id).
  bool has_writer(std::uint64_t writer_id) const;

  struct State;  // shared with the handles, which may outlive the bus

 private:
  std::shared_ptr<State> state_;
};

}  // namespace robodds
