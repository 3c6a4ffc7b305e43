#pragma once
// Test-only Bus: a write calls every reader callback of the topic at once, on the writer's
// thread (like Fast DDS intra-process delivery). Enough to drive the lockstep host loop and
// coordinator without DDS.

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "runtime/bus.hpp"

namespace robodds::test_support {

class LoopbackBus : public Bus {
 public:
  std::shared_ptr<WriterHandle> writer(const std::string& topic, const std::string&, const std::string&) override {
    return std::make_shared<Writer>(this, topic);
  }
  std::shared_ptr<ReaderHandle> reader(const std::string& topic, const std::string&, const std::string&,
                                       SampleCallback on_sample, ReaderEventCallback) override {
    callbacks_[topic].push_back(std::move(on_sample));
    return std::make_shared<ReaderHandle>();
  }
  void flush(std::chrono::milliseconds) override {}

 private:
  class Writer : public WriterHandle {
   public:
    Writer(LoopbackBus* bus, std::string topic) : bus_(bus), topic_(std::move(topic)) {}
    void write(const void* sample) override {
      for (const SampleCallback& callback : bus_->callbacks_[topic_]) {
        callback(sample);
      }
    }
    const std::string& topic() const override { return topic_; }

   private:
    LoopbackBus* bus_;
    std::string topic_;
  };

  std::map<std::string, std::vector<SampleCallback>> callbacks_;
};

}  // namespace robodds::test_support
