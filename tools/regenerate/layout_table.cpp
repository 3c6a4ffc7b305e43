#include "tools/regenerate/layout_table.hpp"

#include <algorithm>
#include <stdexcept>

#include "tools/component/executable_name.hpp"

namespace robodds {
namespace {

std::string code(const std::string& text) { return "`" + text + "`"; }

/// A description as one table cell: a '|' of its own would end the cell.
std::string cell(const std::string& text) {
  std::string escaped;
  for (const char c : text) {
    escaped += c == '|' ? std::string("\\|") : std::string(1, c);
  }
  return escaped;
}

bool ends_with(const std::string& text, const std::string& suffix) {
  return text.size() >= suffix.size() && text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::vector<RegisteredFolder> by_folder(std::vector<RegisteredFolder> rows) {
  std::sort(rows.begin(), rows.end(),
            [](const RegisteredFolder& a, const RegisteredFolder& b) { return a.folder < b.folder; });
  return rows;
}

}  // namespace

std::vector<RegisteredFolder> component_folders(const std::vector<ComponentType>& types) {
  std::vector<RegisteredFolder> rows;
  for (const ComponentType& type : types) {
    const std::string suffix = "/config/" + type.name + ".params.yaml";
    if (!ends_with(type.defaults_file, suffix)) {
      throw std::logic_error("component type '" + type.name + "': defaults file '" + type.defaults_file +
                             "' is not <folder>" + suffix + ", so its folder is unknown");
    }
    rows.push_back({type.defaults_file.substr(0, type.defaults_file.size() - suffix.size()), type.name, type.description});
  }
  return by_folder(rows);
}

std::vector<RegisteredFolder> metrics_module_folders(const std::vector<evaluator::MetricsModuleType>& types) {
  std::vector<RegisteredFolder> rows;
  for (const evaluator::MetricsModuleType& type : types) {
    rows.push_back({type.folder, type.name, type.description});
  }
  return by_folder(rows);
}

std::string render_layout_table(const std::vector<RegisteredFolder>& components,
                                const std::vector<RegisteredFolder>& metrics_modules) {
  std::string table =
      "| component folder | type | executable | what (its registered description) |\n"
      "|---|---|---|---|\n";
  for (const RegisteredFolder& row : components) {
    table += "| " + code(row.folder + "/") + " | " + code(row.name) + " | " + code(component_executable_name(row.name)) +
             " | " + cell(row.description) + " |\n";
  }
  table +=
      "\n"
      "| evaluator's metrics module | module | what (its registered description) |\n"
      "|---|---|---|\n";
  for (const RegisteredFolder& row : metrics_modules) {
    table += "| " + code(row.folder + "/") + " | " + code(row.name) + " | " + cell(row.description) + " |\n";
  }
  return table;
}

}  // namespace robodds
