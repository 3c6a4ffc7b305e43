// `robodds components`: the registered component types and their parameter files;
// `--params NAME` prints one type's parameters (key, type, default, unit, range, description).
#include <cstdio>
#include <string>

#include "tools/robodds/command.hpp"
#include "tools/robodds/params_files.hpp"

namespace robodds {
namespace {

class ComponentsCommand : public Command {
 public:
  ComponentsCommand(CLI::App& app, const CommandEnv& env) : env_(env) {
    cmd_ = app.add_subcommand("components", "list the registered component types");
    cmd_->add_option("--params", params_of_, "print this type's parameters: key, type, default, unit, range, description");
    cmd_->add_flag("--yaml", as_yaml_, "with --params: print the documented defaults file instead of the table");
  }

  bool parsed() const override { return cmd_->parsed(); }

  int run() override {
    if (!params_of_.empty()) {
      std::fputs(component_params_text(env_.registry, params_of_, as_yaml_).c_str(), stdout);
      return 0;
    }
    for (const ComponentType& type : env_.registry.types()) {
      std::printf("%-22s %s\n%-22s params: %s\n", type.name.c_str(), type.description.c_str(), "", type.defaults_file.c_str());
    }
    return 0;
  }

 private:
  const CommandEnv& env_;
  CLI::App* cmd_ = nullptr;
  std::string params_of_;
  bool as_yaml_ = false;
};

}  // namespace

std::unique_ptr<Command> add_components_command(CLI::App& app, const CommandEnv& env) {
  return std::make_unique<ComponentsCommand>(app, env);
}

}  // namespace robodds
