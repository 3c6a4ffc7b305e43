#include "runtime/bus/colocated_bus.hpp"

#include <utility>

#include "runtime/bus/qos_profiles.hpp"

namespace robodds {
namespace {

/// Writes each sample in memory first (this process's readers), then to DDS (observers). A
/// volatile sample is not written to DDS while no reader is matched there: it would reach nobody,
/// and the write (serialisation, keyed history, locks) was the larger part of its cost.
class TeeWriter : public WriterHandle {
 public:
  TeeWriter(std::shared_ptr<WriterHandle> local, std::shared_ptr<WriterHandle> network, bool transient_local)
      : local_(std::move(local)), network_(std::move(network)), transient_local_(transient_local) {}
  void write(const void* sample) override {
    local_->write(sample);
    if (transient_local_ || network_->has_matched_readers()) {
      network_->write(sample);
    }
  }
  const std::string& topic() const override { return local_->topic(); }
  bool wait_acknowledged(std::chrono::milliseconds timeout) override { return network_->wait_acknowledged(timeout); }
  void end_instance(const void* sample) override { network_->end_instance(sample); }

 private:
  std::shared_ptr<WriterHandle> local_;
  std::shared_ptr<WriterHandle> network_;
  bool transient_local_;  // kept for late readers (the mission profile): always written
};

}  // namespace

ColocatedBus::ColocatedBus(Bus& network, ColocatedWorld world, std::set<std::string> produced_here)
    : network_(network), world_(world), produced_here_(std::move(produced_here)) {}

bool ColocatedBus::reads_network(const std::string& topic) const {
  return world_ == ColocatedWorld::kOpen && produced_here_.count(topic) == 0;
}

std::shared_ptr<WriterHandle> ColocatedBus::writer(const std::string& topic, const std::string& type_name,
                                                   const std::string& profile) {
  std::lock_guard<std::mutex> lock(mutex_);
  std::shared_ptr<WriterHandle>& writer = writers_[topic + "|" + profile];
  if (!writer) {
    // The DDS writer first: it checks the profile against the QoS files (ConfigError naming it).
    std::shared_ptr<WriterHandle> network = network_.writer(topic, type_name, profile);
    writer = std::make_shared<TeeWriter>(local_.writer(topic, type_name, profile), std::move(network),
                                         profile == kMissionProfile);
  }
  return writer;
}

std::shared_ptr<ReaderHandle> ColocatedBus::reader(const std::string& topic, const std::string& type_name,
                                                   const std::string& profile, SampleCallback on_sample,
                                                   ReaderEventCallback on_event) {
  if (reads_network(topic)) {
    return network_.reader(topic, type_name, profile, std::move(on_sample), std::move(on_event));
  }
  return local_.reader(topic, type_name, profile, std::move(on_sample), std::move(on_event));
}

std::shared_ptr<ReaderHandle> ColocatedBus::filtered_reader(const std::string& topic, const std::string& type_name,
                                                            const std::string& profile, SampleCallback on_sample,
                                                            ReaderEventCallback on_event, KeyFilter filter) {
  if (reads_network(topic)) {
    return network_.filtered_reader(topic, type_name, profile, std::move(on_sample), std::move(on_event),
                                    std::move(filter));
  }
  return local_.reader(topic, type_name, profile, std::move(on_sample), std::move(on_event));
}

void ColocatedBus::flush(std::chrono::milliseconds timeout) { network_.flush(timeout); }

std::string ColocatedBus::writer_name(std::uint64_t writer_id) const {
  return local_.has_writer(writer_id) ? local_.writer_name(writer_id) : network_.writer_name(writer_id);
}

bool ColocatedBus::writer_runs_any(std::uint64_t writer_id, const std::vector<std::string>& components) const {
  return local_.has_writer(writer_id) || network_.writer_runs_any(writer_id, components);
}

std::map<std::string, std::uint64_t> ColocatedBus::undecodable_samples() const { return network_.undecodable_samples(); }

}  // namespace robodds
