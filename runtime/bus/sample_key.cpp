#include "runtime/bus/sample_key.hpp"

#include "robodds/idl/robodds_visit.hpp"

namespace robodds {
namespace {

template <class T>
std::uint64_t key_of(const void* sample) {
  return idl::instance_key(*static_cast<const T*>(sample));
}

template <class T>
SampleSteps steps_of(const void* sample) {
  const auto& header = static_cast<const T*>(sample)->header();
  return SampleSteps{header.step(), header.next_step()};
}

}  // namespace

SampleKeyFunction sample_key_function(const std::string& type_name) {
  SampleKeyFunction key = nullptr;
  idl::dispatch_type(type_name, [&key](auto tag) {
    using T = typename decltype(tag)::type;
    key = &key_of<T>;
  });
  return key;
}

SampleStepsFunction sample_steps_function(const std::string& type_name) {
  SampleStepsFunction steps = nullptr;
  idl::dispatch_type(type_name, [&steps](auto tag) {
    using T = typename decltype(tag)::type;
    steps = &steps_of<T>;
  });
  return steps;
}

}  // namespace robodds
