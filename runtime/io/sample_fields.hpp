#pragma once
// Generic per-field operations on IDL samples, built on the generated visit_fields().

#include <array>
#include <cmath>
#include <string>
#include <type_traits>
#include <vector>

#include "robodds/idl/robodds_visit.hpp"

namespace robodds {

namespace detail {
template <class T>
struct IsVector : std::false_type {};
template <class T, class A>
struct IsVector<std::vector<T, A>> : std::true_type {};
}  // namespace detail

/// Name of the first NaN/Inf floating-point field of `sample` (recursing into sequences), or
/// an empty string if every numeric field is finite.
template <class Msg>
std::string first_non_finite_field(const Msg& sample) {
  std::string bad;
  auto check = [&bad](const char* name, const auto& value) {
    using V = std::decay_t<decltype(value)>;
    if (!bad.empty()) {
      return;
    }
    if constexpr (std::is_floating_point_v<V>) {
      if (!std::isfinite(value)) {
        bad = name;
      }
    } else if constexpr (detail::IsVector<V>::value) {
      for (std::size_t i = 0; i < value.size() && bad.empty(); ++i) {
        using E = std::decay_t<decltype(value[i])>;
        if constexpr (std::is_floating_point_v<E>) {
          if (!std::isfinite(value[i])) {
            bad = std::string(name) + "[" + std::to_string(i) + "]";
          }
        } else if constexpr (std::is_class_v<E>) {
          const std::string inner = first_non_finite_field(value[i]);
          if (!inner.empty()) {
            bad = std::string(name) + "[" + std::to_string(i) + "]." + inner;
          }
        }
      }
    }
  };
  idl::visit_fields(sample, check);
  return bad;
}

}  // namespace robodds
