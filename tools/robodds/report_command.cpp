// `robodds report OUT_DIR`: (re)draws the plots of a run from its CSVs.
#include "runtime/launch/launch.hpp"
#include "tools/robodds/command.hpp"

namespace robodds {
namespace {

class ReportCommand : public Command {
 public:
  explicit ReportCommand(CLI::App& app) {
    cmd_ = app.add_subcommand("report", "(re)generate the plots of a run from its CSVs");
    cmd_->add_option("out_dir", out_dir_, "output directory of a run")->required();
  }

  bool parsed() const override { return cmd_->parsed(); }

  int run() override { return draw_plots(out_dir_); }

 private:
  CLI::App* cmd_ = nullptr;
  std::string out_dir_;
};

}  // namespace

std::unique_ptr<Command> add_report_command(CLI::App& app, const CommandEnv&) { return std::make_unique<ReportCommand>(app); }

}  // namespace robodds
