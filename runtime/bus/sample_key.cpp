#include "runtime/bus/sample_key.hpp"

#include "robodds/idl/robodds_visit.hpp"

namespace robodds {
namespace {

template <class T>
struct KeyOf {
  static std::uint64_t get(const void* sample) { return idl::instance_key(*static_cast<const T*>(sample)); }
};

template <class T>
struct StepsOf {
  static SampleSteps get(const void* sample) {
    const auto& header = static_cast<const T*>(sample)->header();
    return SampleSteps{header.step(), header.next_step()};
  }
};

/// `Of<T>::get` for the IDL type T named `type_name`, or nullptr when no IDL type has that name.
template <template <class> class Of, class Function>
Function for_type(const std::string& type_name) {
  Function function = nullptr;
  idl::dispatch_type(type_name, [&function](auto tag) {
    using T = typename decltype(tag)::type;
    function = &Of<T>::get;
  });
  return function;
}

}  // namespace

SampleKeyFunction sample_key_function(const std::string& type_name) {
  return for_type<KeyOf, SampleKeyFunction>(type_name);
}

SampleStepsFunction sample_steps_function(const std::string& type_name) {
  return for_type<StepsOf, SampleStepsFunction>(type_name);
}

}  // namespace robodds
