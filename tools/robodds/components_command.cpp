// `robodds components`: the registered component types and their parameter files.
#include <cstdio>

#include "tools/robodds/command.hpp"

namespace robodds {
namespace {

class ComponentsCommand : public Command {
 public:
  ComponentsCommand(CLI::App& app, const CommandEnv& env) : env_(env) {
    cmd_ = app.add_subcommand("components", "list the registered component types");
  }

  bool parsed() const override { return cmd_->parsed(); }

  int run() override {
    for (const ComponentType& type : env_.registry.types()) {
      std::printf("%-22s %s\n%-22s params: %s\n", type.name.c_str(), type.description.c_str(), "", type.defaults_file.c_str());
    }
    return 0;
  }

 private:
  const CommandEnv& env_;
  CLI::App* cmd_ = nullptr;
};

}  // namespace

std::unique_ptr<Command> add_components_command(CLI::App& app, const CommandEnv& env) {
  return std::make_unique<ComponentsCommand>(app, env);
}

}  // namespace robodds
