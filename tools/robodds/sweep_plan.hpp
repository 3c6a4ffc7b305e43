#pragma once
// `robodds sweep`: the list of runs of a Monte Carlo sweep (seeds x parameter grid) and its
// sweep.json. Nothing runs here.

#include <cstdint>
#include <string>
#include <vector>

namespace robodds::sweep {

/// One `--set component.parameter=v1,v2,...`: a grid axis (a single value is an axis of one).
struct GridAxis {
  std::string key;                  // "component.parameter"
  std::vector<std::string> values;  // YAML text of each value, e.g. "0.1" or "[1, 2]"
};

/// One run: a seed with one value of every axis.
struct PlannedRun {
  std::size_t index = 0;        // 0-based, in plan order (combination-major, then seed)
  std::size_t combination = 0;  // index into combinations(axes)
  std::uint64_t seed = 0;
  std::vector<std::string> sets;  // "component.parameter=value", one per axis
};

/// "1-100", "7", "1,3,10-12" -> the seeds in that order. Throws std::invalid_argument naming
/// `text` for an empty list or part, a reversed range, a non-number, a negative seed, or a seed given twice.
std::vector<std::uint64_t> parse_seeds(const std::string& text);

/// "controller.epsilon_m=0.1,0.01" -> {key, {"0.1", "0.01"}}. Commas inside [...] or {...} belong
/// to the value ("pf.list=[1,2],[3,4]" is two values). Throws std::invalid_argument naming `text`
/// if it is not component.parameter=value[,value...] or has an empty value.
GridAxis parse_grid_axis(const std::string& text);

/// Number of value combinations of `axes` (1 without axes).
std::size_t combination_count(const std::vector<GridAxis>& axes);

/// The values of combination `index` (the last axis varies fastest), as "key=value" assignments.
std::vector<std::string> combination_sets(const std::vector<GridAxis>& axes, std::size_t index);

/// What defines a sweep, as given on the command line; sweep.json in the sweep's folder holds it
/// so that `--run-index` and `--aggregate` see the same runs.
struct SweepSpec {
  std::string scenario_file;          // relative to the sweep's folder (a copy: the folder is self-contained), or absolute
  std::string source;                 // the scenario file it was copied from (for the reader)
  std::string seeds;                  // the --seeds text
  std::vector<std::string> grid;      // the --set texts
  std::vector<std::string> run_args;  // passed to every `robodds run` (e.g. --duration 50)
  double run_timeout_s = 3600.0;      // a run still going after this is killed and recorded as failed
};

/// The grid axes of `spec.grid` (parse_grid_axis of each --set text).
std::vector<GridAxis> grid_axes(const SweepSpec& spec);

/// sweep.json text of `spec` (plus the run count, for the reader).
std::string spec_json(const SweepSpec& spec);

/// Reads sweep.json (std::runtime_error naming the file and the key if it is not one).
SweepSpec read_spec(const std::string& path);

/// Every combination x seed. Throws std::invalid_argument if two axes name the same key.
std::vector<PlannedRun> plan_runs(const std::vector<std::uint64_t>& seeds, const std::vector<GridAxis>& axes);

}  // namespace robodds::sweep
