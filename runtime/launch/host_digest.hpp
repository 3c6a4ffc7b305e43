#pragma once
// The digest of what a host of a scenario run loaded (runtime/bus/run_digest.hpp): what every
// host of the run must share. Counted: the scenario file's content (it includes no other file),
// the run options every host is given alike (the effective seed and duration, every --set, the
// --params file's content), each QoS file and the DDS Security governance. Not counted: what is
// each host's own (--out, --log, --group, --member, --domain, the participant's identity files).

#include <string>
#include <vector>

#include "runtime/bus/run_digest.hpp"
#include "runtime/config/scenario.hpp"
#include "runtime/dds/dds_bus.hpp"

namespace robodds {

RunDigest host_digest(const Scenario& scenario, const std::string& params_file, const std::vector<std::string>& sets,
                      const DdsOptions& dds);

}  // namespace robodds
