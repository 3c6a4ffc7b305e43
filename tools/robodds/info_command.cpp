// `robodds info FILE.mcap`: topics, schemas, counts, times, rates, chunks, summary and CRC status
// of a recording (runtime/mcap/mcap_info.hpp prints it). A truncated file (a recorder killed with
// SIGKILL) prints what was recovered and exits 0 with a warning; a damaged one (a CRC or a summary
// that disagrees with the records) prints what it could read, one line per problem, and exits 1; a
// file with nothing readable (missing, not MCAP) is one error line, exit 2.
#include <iostream>

#include "runtime/mcap/mcap_info.hpp"
#include "runtime/mcap/mcap_reader.hpp"
#include "tools/robodds/command.hpp"

namespace robodds {
namespace {

class InfoCommand : public Command {
 public:
  explicit InfoCommand(CLI::App& app) {
    cmd_ = app.add_subcommand("info", "describe an MCAP recording: topics, types, counts, times, rates, compression, summary");
    cmd_->add_option("file", path_, "the .mcap file")->required();
  }

  bool parsed() const override { return cmd_->parsed(); }

  int run() override {
    // Counts only: the messages' bytes are not kept, so a file larger than memory is fine.
    const mcap::ReadReport report = mcap::scan_mcap(path_, mcap::OnDamage::kRecover, nullptr);
    std::cout << mcap::format_info(report) << std::flush;
    if (report.truncated_at) std::cerr << "robodds info: warning: " << path_ << ": " << report.recovery() << "\n";
    if (!report.problems.empty()) {
      std::cerr << "robodds info: " << path_ << ": damaged (" << report.problems.size()
                << (report.problems.size() == 1 ? " problem" : " problems") << ", listed above)\n";
      return 1;
    }
    return 0;
  }

 private:
  CLI::App* cmd_ = nullptr;
  std::string path_;
};

}  // namespace

std::unique_ptr<Command> add_info_command(CLI::App& app, const CommandEnv&) { return std::make_unique<InfoCommand>(app); }

}  // namespace robodds
