#include "tools/robodds/run_report.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <map>

namespace robodds {
namespace {

constexpr int kDefaultSignificant = 3;
constexpr std::size_t kLabelWidth = 18;  // "stage pf_baseline" and a space
constexpr std::size_t kMaxItemsPerLine = 3;  // rejected/adjusted inputs, warnings: the rest counted

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> out{""};
  for (char c : text) {
    if (c == separator) {
      out.emplace_back();
    } else {
      out.back() += c;
    }
  }
  return out;
}

/// "phase*" matches "phase1"; a pattern without "*" only itself.
bool matches(const std::string& pattern, const std::string& name) {
  const std::size_t star = pattern.find('*');
  if (star == std::string::npos) {
    return pattern == name;
  }
  const std::string head = pattern.substr(0, star);
  const std::string tail = pattern.substr(star + 1);
  return name.size() >= head.size() + tail.size() && name.compare(0, head.size(), head) == 0 &&
         name.compare(name.size() - tail.size(), tail.size(), tail) == 0;
}

std::string unquoted(const std::string& json) {
  return json.size() >= 2 && json.front() == '"' && json.back() == '"' ? json.substr(1, json.size() - 2) : json;
}

/// A leaf as the report shows it: integers as written, other numbers rounded, a time of -1 as
/// "never" (the evaluator's "-1: never"), a non-finite figure as "n/a", strings unquoted.
std::string shown(const std::string& key, const SummaryLeaf& leaf, int significant) {
  if (!leaf.number) {
    return leaf.json == "null" ? "n/a" : unquoted(leaf.json);
  }
  const double value = *leaf.number;
  if (is_never(key, value)) {
    return "never";
  }
  if (leaf.json.find_first_of(".eE") == std::string::npos) {
    return leaf.json;  // a count
  }
  return round_significant(value, significant);
}

/// `text` with {key} / {key:N} replaced from `leaves` below `prefix` and {*} by `match`; nullopt
/// when a key is missing. The leaves' paths it used are appended to `used`.
std::optional<std::string> fill(const std::string& text, const std::string& prefix, const std::string& match,
                                const std::map<std::string, const SummaryLeaf*>& leaves, std::vector<std::string>& used) {
  std::string out;
  std::size_t at = 0;
  while (at < text.size()) {
    const std::size_t open = text.find('{', at);
    const std::size_t close = open == std::string::npos ? std::string::npos : text.find('}', open);
    if (close == std::string::npos) {
      out += text.substr(at);
      break;
    }
    out += text.substr(at, open - at);
    std::string key = text.substr(open + 1, close - open - 1);
    at = close + 1;
    if (key == "*") {
      out += match;
      continue;
    }
    int significant = kDefaultSignificant;
    const std::size_t colon = key.find(':');
    if (colon != std::string::npos) {
      significant = std::max(1, std::atoi(key.c_str() + colon + 1));
      key.resize(colon);
    }
    const auto leaf = leaves.find(prefix + key);
    if (leaf == leaves.end()) {
      return std::nullopt;
    }
    used.push_back(leaf->first);
    const std::string value = shown(key, *leaf->second, significant);
    out += value;
    const bool unit_s_follows =
        text.compare(at, 2, " s") == 0 && (at + 2 == text.size() || !std::isalnum(static_cast<unsigned char>(text[at + 2])));
    if (value == "never" && unit_s_follows) {
      at += 2;  // "never", not "never s"
    }
  }
  return out;
}

std::string padded(const std::string& label) {
  return label + std::string(label.size() < kLabelWidth ? kLabelWidth - label.size() : 1, ' ');
}

/// "a; b; c; +2 more" from at most kMaxItemsPerLine items.
std::string joined(const std::vector<std::string>& items, const std::string& rest) {
  std::string out;
  for (std::size_t i = 0; i < items.size() && i < kMaxItemsPerLine; ++i) {
    out += (i == 0 ? "" : "; ") + items[i];
  }
  if (items.size() > kMaxItemsPerLine) {
    out += "; +" + std::to_string(items.size() - kMaxItemsPerLine) + " more " + rest;
  }
  return out;
}

const SummaryLeaf* find(const std::vector<SummaryLeaf>& leaves, const std::string& path) {
  for (const SummaryLeaf& leaf : leaves) {
    if (leaf.path == path) {
      return &leaf;
    }
  }
  return nullptr;
}

/// The non-zero "inputs.<component>.<topic>.<kind>.<reason>" leaves, one item per input:
/// "component topic: N reason, M reason".
std::vector<std::string> input_counts(const std::vector<SummaryLeaf>& leaves, const std::string& kind) {
  std::vector<std::string> out;
  std::string last_input;
  for (const SummaryLeaf& leaf : leaves) {
    const std::vector<std::string> parts = split(leaf.path, '.');
    if (parts.size() == 5 && parts[0] == "inputs" && parts[3] == kind && leaf.number && *leaf.number > 0) {
      const std::string input = parts[1] + " " + parts[2];
      if (input == last_input) {
        out.back() += ", " + leaf.json + " " + parts[4];
      } else {
        out.push_back(input + ": " + leaf.json + " " + parts[4]);
        last_input = input;
      }
    }
  }
  return out;
}

/// What went wrong on the way without failing the run: the hosts' health, warnings logged.
std::vector<std::string> warnings(const RunReportInput& in) {
  std::vector<std::string> out;
  for (const SummaryLeaf& leaf : in.summary) {
    const std::vector<std::string> parts = split(leaf.path, '.');
    if (parts.size() < 3 || parts[0] != "hosts") {
      continue;
    }
    const std::string& host = parts[1];
    const bool positive = leaf.number && *leaf.number > 0;
    if (parts.size() == 3 && parts[2] == "missed_steps" && positive) {
      out.push_back("host " + host + " missed " + leaf.json + " real-time steps");
    } else if (parts.size() == 3 && parts[2] == "late_steps" && positive) {
      out.push_back("host " + host + ": " + leaf.json + " late steps");
    } else if (parts.size() == 4 && parts[2] == "undecodable" && positive) {
      out.push_back("host " + host + ": " + leaf.json + " undecodable samples (" + parts[3] + ")");
    } else if (parts.size() == 3 && parts[2] == "reported" && leaf.json == "false") {
      out.push_back("host " + host + " did not report");
    }
  }
  if (in.warnings_logged > 0) {
    out.push_back(std::to_string(in.warnings_logged) + " warning" + (in.warnings_logged == 1 ? "" : "s") + " logged above");
  }
  return out;
}

std::string status_line(const RunReportInput& in) {
  const SummaryLeaf* status = find(in.summary, "status");
  std::string line = status != nullptr ? unquoted(status->json) : "done";
  std::optional<std::uint64_t> ticks = in.ticks;
  if (!ticks) {
    if (const SummaryLeaf* steps = find(in.summary, "steps"); steps != nullptr && steps->number) {
      ticks = static_cast<std::uint64_t>(*steps->number);
    }
  }
  std::optional<double> wall_s = in.wall_s;
  if (!wall_s) {
    if (const SummaryLeaf* wall = find(in.summary, "run.wall_time_s"); wall != nullptr && wall->number) {
      wall_s = *wall->number;
    }
  }
  if (ticks) {
    // Step 0 is at t = 0: N ticks span (N - 1) steps of simulated time.
    const double sim_s = static_cast<double>(*ticks > 0 ? *ticks - 1 : 0) * in.step_s;
    line += ": " + round_significant(sim_s, 4) + " s simulated";
    if (wall_s && *wall_s > 0.0) {  // a failed run's summary may say 0
      line += " in " + round_significant(*wall_s, 3) + " s (" + round_significant(sim_s / *wall_s, 3) + "x real time)";
    }
  }
  if (const SummaryLeaf* stopped = find(in.summary, "stopped_by"); stopped != nullptr) {
    line += ", stopped by " + unquoted(stopped->json);
  }
  return line;
}

}  // namespace

std::string round_significant(double value, int significant) {
  if (!std::isfinite(value)) {
    return "n/a";
  }
  if (value == 0.0) {
    return "0";
  }
  const int magnitude = static_cast<int>(std::floor(std::log10(std::fabs(value))));
  const int decimals = std::clamp(significant - 1 - magnitude, 0, 12);
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  std::string out = text;
  if (out.find('.') != std::string::npos) {
    out.erase(out.find_last_not_of('0') + 1);
    if (out.back() == '.') {
      out.pop_back();
    }
  }
  return out == "-0" ? "0" : out;
}

std::vector<std::string> headline_lines(const evaluator::Headline& headline, const std::vector<SummaryLeaf>& summary,
                                        std::vector<std::string>* used_paths) {
  std::map<std::string, const SummaryLeaf*> leaves;
  for (const SummaryLeaf& leaf : summary) {
    leaves.emplace(leaf.path, &leaf);
  }
  std::vector<std::string> out;
  for (const evaluator::HeadlineLine& line : headline) {
    // The objects `scope` names below "metrics" (several with a "*"), in file order.
    const std::vector<std::string> pattern = line.scope.empty() ? std::vector<std::string>{} : split(line.scope, '.');
    std::vector<std::pair<std::string, std::string>> scopes;  // prefix, what "*" matched
    if (pattern.empty()) {
      scopes.emplace_back("metrics.", "");
    }
    for (const SummaryLeaf& leaf : pattern.empty() ? std::vector<SummaryLeaf>{} : summary) {
      const std::vector<std::string> parts = split(leaf.path, '.');
      if (parts.size() < pattern.size() + 2 || parts[0] != "metrics") {
        continue;
      }
      std::string prefix = "metrics.";
      std::string match;
      bool ok = true;
      for (std::size_t i = 0; i < pattern.size() && ok; ++i) {
        ok = matches(pattern[i], parts[i + 1]);
        prefix += parts[i + 1] + ".";
        if (pattern[i].find('*') != std::string::npos) {
          match = parts[i + 1];
        }
      }
      if (ok && std::find(scopes.begin(), scopes.end(), std::make_pair(prefix, match)) == scopes.end()) {
        scopes.emplace_back(prefix, match);
      }
    }
    for (const auto& [prefix, match] : scopes) {
      std::vector<std::string> used;
      const std::optional<std::string> label = fill(line.label, prefix, match, leaves, used);
      const std::optional<std::string> text = fill(line.text, prefix, match, leaves, used);
      if (label && text) {
        out.push_back("  " + padded(*label) + *text);
        if (used_paths != nullptr) {
          used_paths->insert(used_paths->end(), used.begin(), used.end());
        }
      }
    }
  }
  return out;
}

std::vector<std::string> run_report_lines(const RunReportInput& in) {
  std::vector<std::string> out{status_line(in)};
  if (const SummaryLeaf* reason = find(in.summary, "reason"); reason != nullptr) {
    out.push_back("  " + padded("reason") + unquoted(reason->json));
  }
  // Issue 27: whether the mission was accomplished, or why not (summary.json "mission"); it takes
  // one of the figures' lines, so the report stays within its 15.
  const SummaryLeaf* mission = find(in.summary, "mission");
  if (mission != nullptr) {
    out.push_back("  " + padded("mission") + unquoted(mission->json));
  }
  if (in.summary.empty() && !in.summary_note.empty()) {
    out.push_back("  (" + in.summary_note + ")");
  }
  std::vector<std::string> figures = headline_lines(in.headline, in.summary);
  const std::size_t max_figures = kMaxHeadlineLines - (mission != nullptr ? 1 : 0);
  if (figures.size() > max_figures) {
    const std::size_t more = figures.size() - (max_figures - 1);
    figures.resize(max_figures - 1);
    figures.push_back("  (+" + std::to_string(more) + " more lines: --verbose, or summary.json)");
  }
  out.insert(out.end(), figures.begin(), figures.end());
  const std::vector<std::string> rejected = input_counts(in.summary, "rejected");
  if (!rejected.empty()) {
    out.push_back("  " + padded("rejected inputs") + joined(rejected, "in summary.json \"inputs\""));
  }
  const std::vector<std::string> adjusted = input_counts(in.summary, "adjusted");
  if (!adjusted.empty()) {
    out.push_back("  " + padded("adjusted inputs") + joined(adjusted, "in summary.json \"inputs\""));
  }
  const std::vector<std::string> warned = warnings(in);
  if (!warned.empty()) {
    out.push_back("  " + padded("warnings") + joined(warned, "in summary.json \"hosts\""));
  }
  std::string files;
  if (!in.summary.empty()) {
    files += "summary.json, ";
  }
  files += std::to_string(in.csv_files) + " CSV files";
  if (in.plot_files > 0) {
    files += ", " + std::to_string(in.plot_files) + " plots";
  }
  out.push_back("results: " + in.out_dir + " (" + files + "; --verbose prints every figure)");
  return out;
}

}  // namespace robodds
