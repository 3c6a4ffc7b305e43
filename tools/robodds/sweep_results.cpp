#include "tools/robodds/sweep_results.hpp"

#include <algorithm>
#include <cstdio>
#include <map>

#include "common/number_text.hpp"
#include "tools/robodds/summary_table.hpp"

namespace robodds::sweep {
namespace {

constexpr const char* kMetricsPrefix = "metrics.";

/// A CSV cell: quoted (inner quotes doubled) when it holds a comma, a quote or a line break.
std::string csv_cell(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) {
    return text;
  }
  std::string out = "\"";
  for (const char c : text) {
    out += c == '"' ? std::string("\"\"") : std::string(1, c);
  }
  return out + "\"";
}

/// The value part of "key=value".
std::string assigned_value(const std::string& assignment) { return assignment.substr(assignment.find('=') + 1); }

/// Metric names in order of first appearance over `outcomes`.
std::vector<std::string> metric_order(const std::vector<RunOutcome>& outcomes) {
  std::vector<std::string> order;
  std::map<std::string, bool> seen;
  for (const RunOutcome& o : outcomes) {
    for (const auto& [name, value] : o.metrics) {
      if (!seen[name]) {
        seen[name] = true;
        order.push_back(name);
      }
    }
  }
  return order;
}

/// Four significant digits, for the Markdown table (the CSVs keep every digit).
std::string brief(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", v);
  return text;
}

std::string combination_title(const std::vector<GridAxis>& axes, const std::vector<std::string>& sets) {
  if (axes.empty()) {
    return "all runs";
  }
  std::string title;
  for (const std::string& s : sets) {
    title += (title.empty() ? "" : ", ") + s;
  }
  return title;
}

}  // namespace

std::vector<std::pair<std::string, double>> read_metrics(const std::string& path) { return metrics_of(summary_leaves(path)); }

std::vector<std::pair<std::string, double>> metrics_of(const std::vector<SummaryLeaf>& leaves) {
  std::vector<std::pair<std::string, double>> out;
  const std::string prefix = kMetricsPrefix;
  for (const SummaryLeaf& leaf : leaves) {
    if (leaf.number && leaf.path.compare(0, prefix.size(), prefix) == 0) {
      out.emplace_back(leaf.path.substr(prefix.size()), *leaf.number);
    }
  }
  return out;
}

std::vector<MetricStats> aggregate(const std::vector<RunOutcome>& outcomes) {
  std::size_t combinations = 0;
  for (const RunOutcome& o : outcomes) {
    combinations = std::max(combinations, o.run.combination + 1);
  }
  const std::vector<std::string> order = metric_order(outcomes);
  std::vector<MetricStats> rows;
  for (std::size_t c = 0; c < combinations; ++c) {
    std::map<std::string, std::vector<double>> values;
    std::map<std::string, std::size_t> never;
    for (const RunOutcome& o : outcomes) {
      if (o.ok && o.run.combination == c) {
        for (const auto& [name, value] : o.metrics) {
          if (is_never(name, value)) {
            ++never[name];
          } else {
            values[name].push_back(value);
          }
        }
      }
    }
    for (const std::string& name : order) {
      const auto it = values.find(name);
      const auto nv = never.find(name);
      if (it == values.end() && nv == never.end()) {
        continue;
      }
      MetricStats row{c, name, {}, nv == never.end() ? 0 : nv->second};
      if (it != values.end()) {
        row.summary = stats::summarize(it->second);
      }
      rows.push_back(row);
    }
  }
  return rows;
}

std::string runs_csv(const std::vector<GridAxis>& axes, const std::vector<RunOutcome>& outcomes) {
  const std::vector<std::string> metrics = metric_order(outcomes);
  std::string out = "run,seed";
  for (const GridAxis& axis : axes) {
    out += "," + csv_cell(axis.key);
  }
  out += ",status,exit_code,wall_s,error";
  for (const std::string& m : metrics) {
    out += "," + csv_cell(m);
  }
  out += "\n";
  for (const RunOutcome& o : outcomes) {
    out += std::to_string(o.run.index) + "," + std::to_string(o.run.seed);
    for (const std::string& s : o.run.sets) {
      out += "," + csv_cell(assigned_value(s));
    }
    out += std::string(",") + (o.ok ? "ok" : o.not_run ? "not run" : "failed") + "," + std::to_string(o.exit_code) + "," + shortest_text(o.wall_s) + "," +
           csv_cell(o.error);
    std::map<std::string, double> by_name(o.metrics.begin(), o.metrics.end());
    for (const std::string& m : metrics) {
      const auto it = by_name.find(m);
      out += "," + (it == by_name.end() ? std::string() : shortest_text(it->second));
    }
    out += "\n";
  }
  return out;
}

std::string summary_csv(const std::vector<GridAxis>& axes, const std::vector<MetricStats>& rows) {
  std::string out;
  for (const GridAxis& axis : axes) {
    out += csv_cell(axis.key) + ",";
  }
  out += "metric,n,mean,std,min,max,ci95,never\n";
  for (const MetricStats& r : rows) {
    for (const std::string& s : combination_sets(axes, r.combination)) {
      out += csv_cell(assigned_value(s)) + ",";
    }
    const stats::SampleSummary& s = r.summary;
    const bool any = s.count >= 1;     // every run "never": no statistics, empty cells
    const bool spread = s.count >= 2;  // one value has no standard deviation or interval: empty cells
    const auto cell = [](bool shown, double v) { return shown ? shortest_text(v) : std::string(); };
    out += csv_cell(r.metric) + "," + std::to_string(s.count) + "," + cell(any, s.mean) + "," + cell(spread, s.stddev) + "," +
           cell(any, s.min) + "," + cell(any, s.max) + "," + cell(spread, s.ci95) + "," + std::to_string(r.never) + "\n";
  }
  return out;
}

std::string summary_markdown(const std::vector<GridAxis>& axes, const std::vector<RunOutcome>& outcomes,
                             const std::vector<MetricStats>& rows) {
  const std::size_t combinations = combination_count(axes);
  std::string out;
  for (std::size_t c = 0; c < combinations; ++c) {
    std::size_t ok = 0;
    std::size_t failed = 0;
    std::size_t not_run = 0;
    for (const RunOutcome& o : outcomes) {
      if (o.run.combination == c) {
        (o.ok ? ok : o.not_run ? not_run : failed) += 1;
      }
    }
    out += "## " + combination_title(axes, combination_sets(axes, c)) + "\n\n" + std::to_string(ok) + " runs ok, " +
           std::to_string(failed) + " failed" + (not_run > 0 ? ", " + std::to_string(not_run) + " not run" : "") + "; mean ± half-width of the 95 % confidence interval (Student t); never: runs whose "
           "time metric (-1) never came, not in n\n\n";
    out += "| metric | n | mean | ± 95 % | std | min | max | never |\n|---|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const MetricStats& r : rows) {
      if (r.combination != c) {
        continue;
      }
      const stats::SampleSummary& s = r.summary;
      const bool any = s.count >= 1;
      const bool spread = s.count >= 2;
      const auto cell = [](bool shown, double v) { return shown ? brief(v) : std::string("n/a"); };
      out += "| " + r.metric + " | " + std::to_string(s.count) + " | " + cell(any, s.mean) + " | " + cell(spread, s.ci95) + " | " +
             cell(spread, s.stddev) + " | " + cell(any, s.min) + " | " + cell(any, s.max) + " | " + std::to_string(r.never) + " |\n";
    }
    out += "\n";
  }
  return out;
}

}  // namespace robodds::sweep
