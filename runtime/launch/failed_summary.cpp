#include "runtime/launch/failed_summary.hpp"

#include <fstream>
#include <sstream>

#include "common/json_writer.hpp"
#include "common/replace_file.hpp"
#include "runtime/base/log.hpp"

namespace robodds {
namespace {

/// Index just past the JSON string that starts at `open` (its opening quote), npos if unclosed.
std::size_t end_of_string(const std::string& text, std::size_t open) {
  for (std::size_t i = open + 1; i < text.size(); ++i) {
    if (text[i] == '\\') {
      ++i;
    } else if (text[i] == '"') {
      return i + 1;
    }
  }
  return std::string::npos;
}

std::string minimal_summary(const std::string& reason) {
  JsonWriter json;
  json.begin_object();
  json.value("status", "failed");
  json.value("reason", reason);
  json.end_object();
  return json.str();
}

}  // namespace

std::string failed_summary_text(const std::string& existing, const std::string& reason) {
  // The evaluator writes "status" as the first key of the object, then "reason" if it failed.
  const std::string status_key = "{\n  \"status\": ";
  if (existing.compare(0, status_key.size(), status_key) != 0) {
    return minimal_summary(reason);
  }
  const std::size_t status_end = end_of_string(existing, status_key.size());
  if (status_end == std::string::npos) {
    return minimal_summary(reason);
  }
  std::string text = status_key + json_escape("failed") + ",\n  \"reason\": " + json_escape(reason);
  std::size_t rest = status_end;
  const std::string reason_key = ",\n  \"reason\": ";
  if (existing.compare(rest, reason_key.size(), reason_key) == 0) {
    rest = end_of_string(existing, rest + reason_key.size());
    if (rest == std::string::npos) {
      return minimal_summary(reason);
    }
  }
  return text + existing.substr(rest);
}

void record_failed_run(const std::string& out_dir, const std::string& reason) {
  if (out_dir.empty()) {
    return;
  }
  const std::string path = out_dir + "/summary.json";
  std::stringstream existing;
  {
    std::ifstream in(path, std::ios::binary);
    existing << in.rdbuf();
  }
  const std::string error = replace_file(path, failed_summary_text(existing.str(), reason));
  if (!error.empty()) {
    log::warn("run", error + ": the run's status is not recorded");
  }
}

}  // namespace robodds
