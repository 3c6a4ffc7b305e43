// `robodds security init SCENARIO --out DIR`: the DDS Security files of a scenario's deployment
// (tools/robodds/security_init.hpp says which files; docs/security.md how to use them).
#include <cstdio>

#include "runtime/host/producer_check.hpp"
#include "runtime/config/scenario.hpp"
#include "tools/robodds/command.hpp"
#include "tools/robodds/security_init.hpp"
#include "tools/robodds/security_policy.hpp"

namespace robodds {
namespace {

/// Topics of each component in either time mode (a deployment may run both).
std::map<std::string, ComponentTopics> both_modes(const ComponentRegistry& registry, const Scenario& scenario) {
  std::map<std::string, ComponentTopics> topics = scenario_component_topics(registry, scenario, TimeMode::kLockstep);
  for (auto& [name, realtime] : scenario_component_topics(registry, scenario, TimeMode::kRealtime)) {
    ComponentTopics& t = topics[name];
    t.publishes.insert(realtime.publishes.begin(), realtime.publishes.end());
    t.subscribes.insert(realtime.subscribes.begin(), realtime.subscribes.end());
    t.wants_run_health = t.wants_run_health || realtime.wants_run_health;
  }
  return topics;
}

class SecurityCommand : public Command {
 public:
  SecurityCommand(CLI::App& app, const CommandEnv& env) : env_(env) {
    cmd_ = app.add_subcommand("security", "DDS Security: identities and signed permissions for a scenario");
    cmd_->require_subcommand(1);
    init_ = cmd_->add_subcommand("init", "create a CA, one identity per group and tool, signed governance and permissions");
    init_->add_option("scenario", scenario_file_, "scenario YAML file")->required();
    init_->add_option("--out", options_.out_dir, "output directory (DIR/<identity>/ per participant)")->required();
    init_->add_option("--days", options_.days, "validity of certificates and permissions (days)")->check(CLI::Range(1, 36500));
    init_->add_flag("--new-ca", options_.new_ca,
                    "replace the CA in DIR/ca (every identity signed by the old one is no longer trusted)");
  }

  bool parsed() const override { return cmd_->parsed(); }

  int run() override {
    const Scenario scenario = load_scenario(scenario_file_);
    const std::vector<SecurityIdentity> identities = security_identities(scenario, both_modes(env_.registry, scenario));
    security_init(scenario, identities, options_);
    std::printf("security files of %s in %s:\n", scenario.name.c_str(), options_.out_dir.c_str());
    for (const SecurityIdentity& identity : identities) {
      std::printf("  %-12s publishes %zu topics, subscribes to %zu\n", identity.name.c_str(), identity.publishes.size(),
                  identity.subscribes.size());
    }
    std::printf("keep %s/ca/ca_key.pem offline; deploy only DIR/<identity>/ to each host\n", options_.out_dir.c_str());
    return 0;
  }

 private:
  const CommandEnv& env_;
  CLI::App* cmd_ = nullptr;
  CLI::App* init_ = nullptr;
  std::string scenario_file_;
  SecurityInitOptions options_;
};

}  // namespace

std::unique_ptr<Command> add_security_command(CLI::App& app, const CommandEnv& env) {
  return std::make_unique<SecurityCommand>(app, env);
}

}  // namespace robodds
