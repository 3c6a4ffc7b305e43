#include "runtime/host/digest_check.hpp"

#include "runtime/base/error.hpp"

namespace robodds {

const DigestVerdict& DigestCheck::verdict(const Bus& bus) {
  if (own_.empty()) {
    return verdict_;
  }
  const std::uint64_t generation = bus.discovery_generation();
  if (!asked_ || generation != generation_) {
    asked_ = true;
    generation_ = generation;
    verdict_ = judge_digests(own_, bus.peer_digests(run_id_));
  }
  return verdict_;
}

std::string DigestCheck::message(const std::string& member, const std::string& difference) {
  return member + ": " + difference + ": " + kAdvice;
}

void DigestCheck::fail_on_difference(const Bus& bus, const std::string& member) {
  const DigestVerdict& v = verdict(bus);
  if (!v.difference.empty()) {
    throw RunConfigError(message(member, v.difference));
  }
}

}  // namespace robodds
