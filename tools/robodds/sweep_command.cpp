// `robodds sweep SCENARIO --seeds 1-100 [--set k=v1,v2 ...] --out DIR`: a Monte Carlo sweep of
// lockstep co-located runs on worker processes, then one table of every summary.json metric.
// Also `--plan` (write the run list only), `--run-index K` (one run of a planned sweep, for a
// batch engine's array task) and `--aggregate` (the tables from the runs' folders).
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <thread>

#include "common/number_text.hpp"
#include "runtime/component/param_keys.hpp"
#include "runtime/base/error.hpp"
#include "runtime/launch/host_args.hpp"
#include "runtime/launch/launch.hpp"
#include "runtime/launch/output_dir.hpp"
#include "runtime/config/share_dir.hpp"
#include "tools/cli/one_of.hpp"
#include "tools/robodds/command.hpp"
#include "tools/robodds/module_headlines.hpp"
#include "tools/robodds/progress.hpp"
#include "tools/robodds/run_report.hpp"
#include "tools/robodds/sweep_emit.hpp"
#include "tools/robodds/sweep_resume.hpp"
#include "tools/robodds/sweep_runner.hpp"

namespace robodds {
namespace {

using namespace sweep;

constexpr int kMaxDomain = 232;

/// The sweep's progress on stderr, as `robodds run`'s (progress.hpp): a live line on a terminal,
/// else a line per 10 % of the runs or every 30 s.
class SweepProgress {
 public:
  SweepProgress() : pacer_(isatty(STDERR_FILENO) != 0) {}

  void operator()(const Progress& p) {
    if (!pacer_.due(p.done, p.total, p.elapsed_s)) {
      return;
    }
    const std::string text = "sweep: " + std::to_string(p.done) + "/" + std::to_string(p.total) + " runs done, " +
                             std::to_string(p.failed) + " failed, " + clock_text(p.elapsed_s) + " elapsed, " +
                             eta_text(p.done, p.total, p.elapsed_s);
    std::fputs(progress_output(text, pacer_.terminal(), p.done >= p.total).c_str(), stderr);
  }

 private:
  ProgressPacer pacer_;
};

/// The rows of the metrics the modules' headline lines show (module_headlines()), found in the
/// first successful run's metrics; every row when none is (a scenario without headline figures).
std::vector<MetricStats> headline_rows(const std::vector<MetricStats>& rows, const std::vector<RunOutcome>& outcomes) {
  std::vector<SummaryLeaf> leaves;
  for (const RunOutcome& o : outcomes) {
    if (o.ok) {
      for (const auto& [name, value] : o.metrics) {
        leaves.push_back({"metrics." + name, shortest_text(value), value});
      }
      break;
    }
  }
  std::vector<std::string> used;
  headline_lines(module_headlines(), leaves, &used);
  std::vector<MetricStats> out;
  for (const MetricStats& row : rows) {
    if (std::find(used.begin(), used.end(), "metrics." + row.metric) != used.end()) {
      out.push_back(row);
    }
  }
  return out.empty() ? rows : out;
}

void write_file(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  if (!out) {
    throw RunError("cannot write " + path);
  }
}

class SweepCommand : public Command {
 public:
  SweepCommand(CLI::App& app, const CommandEnv& env) : env_(env) {
    cmd_ = app.add_subcommand("sweep", "Monte Carlo sweep: a scenario over seeds and a parameter grid on worker processes");
    cmd_->add_option("scenario", scenario_file_, "scenario YAML file (not with --run-index or --aggregate)");
    cmd_->add_option("--seeds", seeds_, "seeds, e.g. 1-100 or 1,5,7-9");
    cmd_->add_option("--set", grid_,
                     "component.parameter=value[,value...]: a grid axis (repeatable; one row per combination), e.g. "
                     "controller.epsilon_m=0.1,0.01");
    jobs_ = std::max(1U, std::thread::hardware_concurrency());
    cmd_->add_option("--jobs", jobs_, "worker processes (default: the number of cores)");
    cmd_->add_option("--out", out_dir_, "the sweep's folder: sweep.json, runs/<k>/, runs.csv, summary.csv, summary.md (required unless --resume)");
    cmd_->add_option("--resume", resume_dir_,
                     "the folder of an interrupted sweep: run only its runs that did not finish (the same scenario, --seeds, "
                     "--set and --duration as it was started with), then write the tables of all");
    cmd_->add_option("--domain", first_domain_,
                     "DDS domain of worker 1; worker j uses domain + j - 1 (default: $ROBODDS_DOMAIN_ID or 0)")
        ->check(CLI::Range(0, kMaxDomain));
    add_duration_option(cmd_, duration_s_, "override the scenario duration (s) of every run");
    cmd_->add_option("--run-timeout", run_timeout_s_, "s, a run still going after this is killed and recorded as failed")
        ->check(CLI::PositiveNumber);
    cmd_->add_flag("--plan", plan_only_, "write sweep.json and plan.txt (the run list) and stop");
    cmd_->add_option("--run-index", run_index_, "run only run K of the sweep already planned in --out (a batch array task)");
    cmd_->add_flag("--aggregate", aggregate_, "only (re)write the tables from the runs in --out");
    cmd_->add_option("--emit", emit_, "write the planned sweep in --out as a batch array job: slurm (slurm.sbatch) or k8s (k8s-job.yaml)")
        ->check(cli::one_of({"slurm", "k8s"}));
    cmd_->add_option("--image", image_, "with --emit k8s: the container image (default robodds:latest, deploy/docker)");
    cmd_->add_option("--claim", claim_, "with --emit k8s: the persistent volume claim holding the sweep folder (default robodds-sweep)");
    cmd_->add_option("--domain-offset", domain_offset_text_,
                     "with --emit: array task K runs on DDS domain (N + K) % 233 (0-232, default 0); give sweeps that may "
                     "share nodes different offsets (docs/scale.md)");
  }

  bool parsed() const override { return cmd_->parsed(); }

  int run() override {
    if (!resume_dir_.empty()) {
      if (!out_dir_.empty() && std::filesystem::weakly_canonical(out_dir_) != std::filesystem::weakly_canonical(resume_dir_)) {
        throw ConfigError("robodds sweep: --resume " + resume_dir_ + " and --out " + out_dir_ + " name different folders (--resume alone is enough)");
      }
      out_dir_ = resume_dir_;
    } else if (out_dir_.empty()) {
      throw ConfigError("robodds sweep: --out DIR is required (or --resume DIR: an interrupted sweep)");
    }
    if (domain_offset_text_ && emit_.empty()) {
      throw ConfigError("robodds sweep: --domain-offset works only with --emit slurm|k8s (a sweep on this machine takes --domain)");
    }
    const int planned_modes = (aggregate_ ? 1 : 0) + (run_index_ ? 1 : 0) + (emit_.empty() ? 0 : 1);
    if (planned_modes > 0) {
      if (!scenario_file_.empty() || !seeds_.empty() || !grid_.empty() || duration_s_ || plan_only_ || planned_modes > 1 ||
          !resume_dir_.empty()) {
        throw ConfigError("robodds sweep: --aggregate, --run-index and --emit work on the sweep planned in --out; they take no "
                          "scenario, --seeds, --set, --duration, --plan or --resume (and not each other)");
      }
      if (!emit_.empty()) {
        const int offset = domain_offset();  // before sweep.json: a bad option is named first
        return emit(read_planned_spec(), offset);
      }
      const SweepSpec spec = read_planned_spec();
      return aggregate_ ? aggregate_existing(spec) : run_one(spec, *run_index_);
    }
    const SweepSpec spec = checked_spec();
    if (!resume_dir_.empty()) {
      if (plan_only_) {
        throw ConfigError("robodds sweep: --plan starts a new sweep; it does not go with --resume");
      }
      return resume(spec);
    }
    std::filesystem::create_directories(out_dir_);
    std::filesystem::copy_file(spec.source, out_dir_ + "/" + spec.scenario_file, std::filesystem::copy_options::overwrite_existing);
    write_file(out_dir_ + "/sweep.json", spec_json(spec));
    const std::vector<PlannedRun> runs = planned_runs(spec);
    if (plan_only_) {
      write_plan_text(spec, runs);
      std::printf("planned %zu runs in %s (sweep.json, plan.txt); run one with: robodds sweep --run-index K --out %s\n",
                  runs.size(), out_dir_.c_str(), out_dir_.c_str());
      return 0;
    }
    std::fprintf(stderr, "sweep: %zu runs (%zu combinations x %zu seeds) on %u workers, domains %d-%d\n", runs.size(),
                 combination_count(grid_axes(spec)), parse_seeds(spec.seeds).size(), jobs_, domain(),
                 domain() + static_cast<int>(jobs_) - 1);
    return finish(spec, run_all(runs, runner_options(spec), SweepProgress()));
  }

 private:
  static std::vector<PlannedRun> planned_runs(const SweepSpec& spec) { return plan_runs(parse_seeds(spec.seeds), grid_axes(spec)); }

  int domain() const {
    if (!resolved_domain_) {
      resolved_domain_ = first_domain_ >= 0 ? first_domain_ : resolve_dds(DdsArgs{}, "robodds-sweep").domain_id;
    }
    return *resolved_domain_;
  }

  /// The sweep of the command line, every part checked before anything runs.
  SweepSpec checked_spec() const {
    if (scenario_file_.empty()) {
      throw ConfigError("robodds sweep: a scenario file is required");
    }
    if (seeds_.empty()) {
      throw ConfigError("robodds sweep: --seeds is required (e.g. --seeds 1-10)");
    }
    if (jobs_ == 0) {
      throw ConfigError("robodds sweep: --jobs must be at least 1");
    }
    if (domain() + static_cast<int>(jobs_) - 1 > kMaxDomain) {
      throw ConfigError("robodds sweep: --jobs " + std::to_string(jobs_) + " from domain " + std::to_string(domain()) +
                        " needs domains up to " + std::to_string(domain() + static_cast<int>(jobs_) - 1) + " (max " +
                        std::to_string(kMaxDomain) + ")");
    }
    if (resume_dir_.empty() && std::filesystem::exists(out_dir_ + "/sweep.json")) {
      throw ConfigError("robodds sweep: --out " + out_dir_ + " holds another sweep (sweep.json); choose another folder or remove it");
    }
    SweepSpec spec;
    spec.scenario_file = "scenario.yaml";
    spec.source = std::filesystem::weakly_canonical(scenario_file_).string();  // ./x.yaml and x.yaml: one file for --resume
    spec.seeds = seeds_;
    spec.grid = grid_;
    if (duration_s_) {
      spec.run_args = {"--duration", shortest_text(*duration_s_)};
    }
    spec.run_timeout_s = run_timeout_s_;
    // A key without its component ('--set epsilon=0.1,0.2'): the plan would only say "expected
    // component.parameter"; the scenario's parameters name the closest instead.
    for (const std::string& text : grid_) {
      if (text.substr(0, text.find('=')).find('.') == std::string::npos && text.find('=') != std::string::npos) {
        try {
          check_param_keys(load_scenario(spec.source), env_.registry, {text}, "--set");
        } catch (const ConfigError& e) {
          throw ConfigError(std::string("robodds sweep: ") + e.what());
        }
      }
    }
    std::vector<PlannedRun> runs;
    try {
      runs = planned_runs(spec);
    } catch (const std::invalid_argument& e) {
      throw ConfigError(std::string("robodds sweep: ") + e.what());
    }
    // Every combination's --set keys against the scenario's components and their parameter tables.
    Scenario scenario = load_scenario(spec.source);
    apply_run_overrides(scenario, duration_s_, std::nullopt);
    const std::vector<GridAxis> axes = grid_axes(spec);
    for (std::size_t c = 0; c < combination_count(axes); ++c) {
      Scenario variant = scenario;
      try {
        apply_param_overrides(variant, parse_param_assignments(combination_sets(axes, c)), "--set");
      } catch (const ConfigError& e) {
        throw ConfigError(std::string("robodds sweep: ") + e.what());
      }
      for (const GridAxis& axis : axes) {
        const ComponentSpec& component = variant.component(axis.key.substr(0, axis.key.find('.')));
        try {
          const ComponentType& type = env_.registry.get(component.type);
          ParamReader reader = scenario_component_params(type, component);  // an unknown key
          if (type.check_params) {
            type.check_params(reader);  // a value of the wrong type or out of range
          }
        } catch (const ConfigError& e) {  // "--set: key: unknown parameter (known: ...)", "--set: key: must be > 0 ..."
          throw ConfigError("robodds sweep: --set " + axis.key + ": component '" + component.name + "' (" + component.type +
                            ") of " + scenario_file_ + ": " + e.what());
        }
      }
    }
    return spec;
  }

  SweepSpec read_planned_spec() const {
    try {
      return read_spec(out_dir_ + "/sweep.json");
    } catch (const std::runtime_error& e) {
      throw ConfigError(std::string("robodds sweep: ") + e.what());
    }
  }

  RunnerOptions runner_options(const SweepSpec& spec) const {
    RunnerOptions o;
    o.robodds = this_executable();
    o.scenario_file = std::filesystem::path(spec.scenario_file).is_absolute() ? spec.scenario_file
                                                                               : out_dir_ + "/" + spec.scenario_file;
    o.out_dir = out_dir_;
    o.jobs = jobs_;
    o.first_domain = domain();
    o.run_timeout_s = spec.run_timeout_s;
    o.run_args = spec.run_args;
    o.stop = &env_.stop;
    return o;
  }

  void write_plan_text(const SweepSpec& spec, const std::vector<PlannedRun>& runs) const {
    std::string text = "# run seed command (robodds sweep --run-index K --out " + out_dir_ + " runs one of them)\n";
    const RunnerOptions o = runner_options(spec);
    for (const PlannedRun& r : runs) {
      text += std::to_string(r.index) + " " + std::to_string(r.seed);
      for (const std::string& arg : run_argv(o, r, o.first_domain)) {
        text += " " + arg;
      }
      text += "\n";
    }
    write_file(out_dir_ + "/plan.txt", text);
  }

  /// --domain-offset, checked (0 when not given).
  int domain_offset() const {
    try {
      return domain_offset_text_ ? parse_domain_offset(*domain_offset_text_) : 0;
    } catch (const std::invalid_argument& e) {
      throw ConfigError(std::string("robodds sweep: ") + e.what());
    }
  }

  int emit(const SweepSpec& spec, int offset) const {
    const std::size_t runs = planned_runs(spec).size();
    const std::string dir = std::filesystem::absolute(out_dir_).lexically_normal().string();
    if (emit_ == "slurm") {
      write_file(out_dir_ + "/slurm.sbatch", slurm_script(dir, runs, offset));
      std::printf("wrote %s/slurm.sbatch (%zu array tasks): sbatch it where the nodes see %s\n", out_dir_.c_str(), runs, dir.c_str());
    } else {
      if (claim_.empty() || dns_label(claim_) != claim_) {
        throw ConfigError("robodds sweep: --claim '" + claim_ + "': a Kubernetes name (lower case letters, digits and '-')");
      }
      if (image_.empty() || image_.find_first_of("\"\\ \n") != std::string::npos) {
        throw ConfigError("robodds sweep: --image '" + image_ + "': not an image reference");
      }
      const std::string name = dns_label("robodds-sweep-" + std::filesystem::path(dir).filename().string());
      write_file(out_dir_ + "/k8s-job.yaml", k8s_job(name, runs, jobs_, image_, claim_, offset));
      std::printf("wrote %s/k8s-job.yaml (Indexed Job %s, %zu completions, %u at a time): copy the folder to the claim %s, "
                  "then kubectl apply -f it\n", out_dir_.c_str(), name.c_str(), runs, jobs_, claim_.c_str());
    }
    return 0;
  }

  /// One planned run in this process's slot (a batch array task): its outcome goes to its folder.
  /// Exit 0 once the run was carried out and recorded, also when its simulation failed (the
  /// aggregate reports it; a batch engine should not retry it); non-zero when it could not run.
  int run_one(const SweepSpec& spec, std::size_t index) const {
    const std::vector<PlannedRun> runs = planned_runs(spec);
    if (index >= runs.size()) {
      throw ConfigError("robodds sweep: --run-index " + std::to_string(index) + ": the sweep in " + out_dir_ + " has runs 0-" +
                        std::to_string(runs.size() - 1));
    }
    RunnerOptions o = runner_options(spec);
    o.jobs = 1;
    const std::vector<RunOutcome> outcome = run_all({runs[index]}, o, [](const Progress&) {});
    if (outcome.front().not_run) {  // a signal (e.g. the batch engine's preemption): not carried out, a retry runs it
      throw RunError("robodds sweep: run " + std::to_string(index) + " was interrupted by a signal; nothing recorded");
    }
    std::printf("run %zu (seed %llu): %s\n", index, static_cast<unsigned long long>(runs[index].seed),
                outcome.front().ok ? "ok" : ("failed (recorded): " + outcome.front().error).c_str());
    return 0;
  }

  /// The outcome of every planned run as recorded in its folder.
  std::vector<RunOutcome> collect_existing(const SweepSpec& spec) const {
    std::vector<RunOutcome> outcomes;
    for (const PlannedRun& r : planned_runs(spec)) {
      outcomes.push_back(recorded_outcome(r, run_dir(out_dir_, r.index)));
    }
    return outcomes;
  }

  /// --aggregate: the tables of the runs recorded in --out, and on stderr each planned run without
  /// a result by index and seed with how to run it again (a batch array task that never ran or was
  /// lost: its index is the one to resubmit). Such runs are not failures (exit 0, as a partial
  /// sweep's tables are still useful); failed runs exit 1 (write_tables).
  int aggregate_existing(const SweepSpec& spec) const {
    const std::vector<RunOutcome> outcomes = collect_existing(spec);
    const int code = write_tables(spec, outcomes);
    std::string indices;
    for (const RunOutcome& o : outcomes) {
      if (!o.not_run) {
        continue;
      }
      std::fprintf(stderr, "sweep: run %zu (seed %llu) has no result in %s: run it with robodds sweep --run-index %zu --out %s\n",
                   o.run.index, static_cast<unsigned long long>(o.run.seed), run_dir(out_dir_, o.run.index).c_str(), o.run.index,
                   out_dir_.c_str());
      indices += (indices.empty() ? "" : ",") + std::to_string(o.run.index);
    }
    if (!indices.empty()) {
      std::fprintf(stderr, "sweep: a batch array job reruns them with its array indices %s (e.g. sbatch --array=%s %s/slurm.sbatch)\n",
                   indices.c_str(), indices.c_str(), out_dir_.c_str());
    }
    return code;
  }

  int write_tables(const SweepSpec& spec, const std::vector<RunOutcome>& outcomes) const {
    const std::vector<GridAxis> axes = grid_axes(spec);
    const std::vector<MetricStats> rows = aggregate(outcomes);
    write_file(out_dir_ + "/runs.csv", runs_csv(axes, outcomes));
    write_file(out_dir_ + "/summary.csv", summary_csv(axes, rows));
    const std::string markdown = summary_markdown(axes, outcomes, rows);
    write_file(out_dir_ + "/summary.md", markdown);
    // On stdout the headline figures' rows only (issue 26: a table a person reads); the files have every metric.
    std::fputs(summary_markdown(axes, outcomes, headline_rows(rows, outcomes)).c_str(), stdout);
    std::size_t failed = 0;
    std::size_t not_run = 0;
    for (const RunOutcome& o : outcomes) {
      if (o.not_run) {
        ++not_run;  // never started or interrupted: --resume runs it, it is no failure
      } else if (!o.ok) {
        ++failed;
        std::fprintf(stderr, "sweep: run %zu (seed %llu) failed: %s\n", o.run.index, static_cast<unsigned long long>(o.run.seed),
                     o.error.c_str());
      }
    }
    const std::string missing = not_run == 0 ? "" : ", " + std::to_string(not_run) + " not run";
    std::printf("tables of every metric: %s/summary.md, summary.csv, runs.csv (%zu runs, %zu failed%s)\n", out_dir_.c_str(), outcomes.size(),
                failed, missing.c_str());
    return failed == 0 ? 0 : 1;
  }

  /// The tables of `outcomes`; after an interruption (the runs it stopped and those never started
  /// are not run) the RunError that ends the sweep with 128 + the signal.
  int finish(const SweepSpec& spec, const std::vector<RunOutcome>& outcomes) const {
    const int code = write_tables(spec, outcomes);
    if (env_.stop.load()) {
      std::size_t finished = 0;
      for (const RunOutcome& o : outcomes) {
        finished += o.not_run ? 0 : 1;
      }
      if (finished == outcomes.size()) {
        return code;  // the signal came after the last run: nothing to resume
      }
      throw RunError("sweep interrupted by a signal after " + std::to_string(finished) + " of " + std::to_string(outcomes.size()) +
                     " runs (the tables cover those); run the rest with the same command and --resume " + out_dir_);
    }
    return code;
  }

  /// --resume: the sweep in out_dir_ must be the one the command line describes; runs only the
  /// planned runs without an outcome (never started, or stopped by an interruption), then writes
  /// the tables of every run.
  int resume(const SweepSpec& given) const {
    if (!std::filesystem::is_directory(out_dir_)) {
      throw ConfigError("robodds sweep: --resume " + out_dir_ + ": no such folder");
    }
    if (!std::filesystem::exists(out_dir_ + "/sweep.json")) {
      throw ConfigError("robodds sweep: --resume " + out_dir_ + ": holds no sweep.json (not a sweep's folder)");
    }
    const SweepSpec planned = read_planned_spec();
    const std::string difference = spec_difference(planned, given);
    if (!difference.empty()) {
      throw ConfigError("robodds sweep: --resume " + out_dir_ + ": not the sweep of this command line: " + difference);
    }
    if (file_text(given.source) != file_text(out_dir_ + "/" + planned.scenario_file)) {
      throw ConfigError("robodds sweep: --resume " + out_dir_ + ": " + scenario_file_ + " has changed since the sweep started (" +
                        out_dir_ + "/" + planned.scenario_file + " is the copy its runs used)");
    }
    std::set<std::size_t> finished;
    const std::vector<PlannedRun> runs = planned_runs(planned);
    for (const PlannedRun& r : runs) {
      if (std::filesystem::exists(run_dir(out_dir_, r.index) + "/outcome.json")) {
        finished.insert(r.index);
      }
    }
    const std::vector<PlannedRun> missing = missing_runs(runs, finished);
    std::fprintf(stderr, "sweep: resuming %s: %zu of %zu runs finished, %zu to run on %u workers, domains %d-%d\n", out_dir_.c_str(),
                 finished.size(), runs.size(), missing.size(), jobs_, domain(), domain() + static_cast<int>(jobs_) - 1);
    const std::vector<RunOutcome> done = run_all(missing, runner_options(planned), SweepProgress());
    std::vector<RunOutcome> outcomes = collect_existing(planned);  // the kept runs and the new ones, from their folders
    for (const RunOutcome& o : done) {
      if (o.not_run) {
        outcomes.at(o.run.index) = o;  // interrupted again: not run (and why)
      }
    }
    return finish(planned, outcomes);
  }

  static std::string file_text(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }

  const CommandEnv& env_;
  CLI::App* cmd_ = nullptr;
  std::string resume_dir_;
  std::string scenario_file_;
  std::string seeds_;
  std::vector<std::string> grid_;
  unsigned jobs_ = 1;
  std::string out_dir_;
  int first_domain_ = -1;
  mutable std::optional<int> resolved_domain_;
  std::optional<double> duration_s_;
  double run_timeout_s_ = 3600.0;
  bool plan_only_ = false;
  std::optional<std::size_t> run_index_;
  bool aggregate_ = false;
  std::string emit_;
  std::string image_ = "robodds:latest";
  std::string claim_ = "robodds-sweep";
  std::optional<std::string> domain_offset_text_;  // checked by parse_domain_offset (the error names it and the reason)
};

}  // namespace

std::unique_ptr<Command> add_sweep_command(CLI::App& app, const CommandEnv& env) { return std::make_unique<SweepCommand>(app, env); }

}  // namespace robodds
