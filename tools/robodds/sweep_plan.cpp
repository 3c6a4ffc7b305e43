#include "tools/robodds/sweep_plan.hpp"

#include <yaml-cpp/yaml.h>

#include <set>
#include <stdexcept>

#include "common/json_writer.hpp"
#include "runtime/config/params.hpp"

namespace robodds::sweep {
namespace {

std::uint64_t parse_seed(const std::string& part, const std::string& text) {
  if (part.empty() || part.find_first_not_of("0123456789") != std::string::npos || part.size() > 20) {
    throw std::invalid_argument("--seeds '" + text + "': '" + part + "' is not a seed (a non-negative integer)");
  }
  try {
    return std::stoull(part);
  } catch (const std::out_of_range&) {
    throw std::invalid_argument("--seeds '" + text + "': '" + part + "' is above the largest seed (2^64 - 1)");
  }
}

std::string trim(const std::string& s) {
  const std::size_t first = s.find_first_not_of(" \t");
  if (first == std::string::npos) {
    return "";
  }
  return s.substr(first, s.find_last_not_of(" \t") - first + 1);
}

}  // namespace

std::vector<std::uint64_t> parse_seeds(const std::string& text) {
  std::vector<std::uint64_t> seeds;
  std::set<std::uint64_t> seen;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    const std::string part = trim(text.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    const std::size_t dash = part.find('-');
    const std::uint64_t first = parse_seed(dash == std::string::npos ? part : part.substr(0, dash), text);
    const std::uint64_t last = dash == std::string::npos ? first : parse_seed(part.substr(dash + 1), text);
    if (last < first) {
      throw std::invalid_argument("--seeds '" + text + "': the range '" + part + "' is empty (reversed)");
    }
    if (last - first >= 1000000) {
      throw std::invalid_argument("--seeds '" + text + "': the range '" + part + "' has more than a million seeds");
    }
    for (std::uint64_t seed = first;; ++seed) {
      if (!seen.insert(seed).second) {
        throw std::invalid_argument("--seeds '" + text + "': seed " + std::to_string(seed) + " is given twice");
      }
      seeds.push_back(seed);
      if (seed == last) {
        break;
      }
    }
    if (comma == std::string::npos) {
      break;
    }
    start = comma + 1;
  }
  return seeds;
}

GridAxis parse_grid_axis(const std::string& text) {
  const auto split = split_param_assignment(text);
  if (!split) {
    throw std::invalid_argument("--set '" + text + "': expected component.parameter=value[,value...] (e.g. controller.epsilon_m=0.1,0.01)");
  }
  GridAxis axis{split->first, {}};
  const std::string& list = split->second;
  int depth = 0;
  std::string value;
  const auto push = [&] {
    const std::string v = trim(value);
    if (v.empty()) {
      throw std::invalid_argument("--set '" + text + "': an empty value");
    }
    axis.values.push_back(v);
    value.clear();
  };
  for (const char c : list) {
    if (c == '[' || c == '{') {
      ++depth;
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    } else if (c == ',' && depth == 0) {
      push();
      continue;
    }
    value += c;
  }
  push();
  return axis;
}

std::size_t combination_count(const std::vector<GridAxis>& axes) {
  std::size_t count = 1;
  for (const GridAxis& axis : axes) {
    count *= axis.values.size();
  }
  return count;
}

std::vector<std::string> combination_sets(const std::vector<GridAxis>& axes, std::size_t index) {
  std::vector<std::string> sets(axes.size());
  for (std::size_t a = axes.size(); a-- > 0;) {
    const std::size_t n = axes[a].values.size();
    sets[a] = axes[a].key + "=" + axes[a].values[index % n];
    index /= n;
  }
  return sets;
}

std::vector<PlannedRun> plan_runs(const std::vector<std::uint64_t>& seeds, const std::vector<GridAxis>& axes) {
  std::set<std::string> keys;
  for (const GridAxis& axis : axes) {
    if (!keys.insert(axis.key).second) {
      throw std::invalid_argument("--set: " + axis.key + " is given twice (list its values in one --set, comma separated)");
    }
  }
  std::vector<PlannedRun> runs;
  for (std::size_t c = 0; c < combination_count(axes); ++c) {
    const std::vector<std::string> sets = combination_sets(axes, c);
    for (const std::uint64_t seed : seeds) {
      runs.push_back(PlannedRun{runs.size(), c, seed, sets});
    }
  }
  return runs;
}

std::vector<GridAxis> grid_axes(const SweepSpec& spec) {
  std::vector<GridAxis> axes;
  for (const std::string& g : spec.grid) {
    axes.push_back(parse_grid_axis(g));
  }
  return axes;
}

std::string spec_json(const SweepSpec& spec) {
  const std::vector<GridAxis> axes = grid_axes(spec);
  JsonWriter w;
  w.begin_object();
  w.value("robodds_sweep", std::int64_t{1});  // format version
  w.value("scenario", spec.scenario_file);
  w.value("source", spec.source);
  w.value("seeds", spec.seeds);
  w.begin_array("set");
  for (const std::string& g : spec.grid) {
    w.value("", g);
  }
  w.end_array();
  w.begin_array("run_args");
  for (const std::string& a : spec.run_args) {
    w.value("", a);
  }
  w.end_array();
  w.value("run_timeout_s", spec.run_timeout_s);
  w.value("runs", static_cast<std::int64_t>(parse_seeds(spec.seeds).size() * combination_count(axes)));
  w.end_object();
  return w.str() + "\n";
}

SweepSpec read_spec(const std::string& path) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);  // JSON is YAML
  } catch (const YAML::Exception& e) {
    throw std::runtime_error(path + ": cannot be read as JSON: " + e.what());
  }
  const auto need = [&](const char* key) {
    if (!root.IsMap() || !root[key]) {
      throw std::runtime_error(path + ": " + key + ": missing (not a robodds sweep.json)");
    }
    return root[key];
  };
  try {
    need("robodds_sweep");
    SweepSpec spec;
    spec.scenario_file = need("scenario").as<std::string>();
    spec.source = need("source").as<std::string>();
    spec.seeds = need("seeds").as<std::string>();
    spec.grid = need("set").as<std::vector<std::string>>();
    spec.run_args = need("run_args").as<std::vector<std::string>>();
    spec.run_timeout_s = need("run_timeout_s").as<double>();
    return spec;
  } catch (const YAML::Exception& e) {
    throw std::runtime_error(path + ": " + e.what());
  }
}

}  // namespace robodds::sweep
