#pragma once
// `robodds sweep ... --resume DIR`: which planned runs are still to do, and whether the command
// line describes the sweep DIR was planned for. Pure: the command reads the folder.

#include <cstddef>
#include <set>
#include <string>
#include <vector>

#include "tools/robodds/sweep_plan.hpp"

namespace robodds::sweep {

/// The runs of `runs` whose index is not in `finished` (those whose folder holds outcome.json:
/// ok or failed), in plan order: the runs never started and those an interruption stopped.
std::vector<PlannedRun> missing_runs(const std::vector<PlannedRun>& runs, const std::set<std::size_t>& finished);

/// What differs between the sweep planned in a folder (`planned`, from its sweep.json) and the one
/// the command line describes (`given`): "" when they define the same runs, else one phrase
/// naming the first option that differs with both values, e.g. "--seeds: '1-4' in sweep.json,
/// '1-6' on the command line". --jobs and --domain may differ: they do not change the runs.
std::string spec_difference(const SweepSpec& planned, const SweepSpec& given);

}  // namespace robodds::sweep
