#include "runtime/host/health_exchange.hpp"

#include <gtest/gtest.h>

#include "runtime/bus/memory_bus.hpp"

namespace robodds {
namespace {

HostHealth sample_health(const std::string& member) {
  HostHealth h;
  h.member = member;
  h.figures.ticks = 1001;
  h.figures.missed_steps = 416;
  h.figures.late_steps = 7;
  h.figures.worst_lateness_s = 0.25;
  InputCounts cmd;
  cmd.accepted = 998;
  cmd.rejected["non_finite"] = 3;
  cmd.adjusted["saturated"] = 2;
  h.components.push_back({"plant", {{"plant/cmd", cmd}, {"plant/state", InputCounts{4, {}, {}}}}});
  h.components.push_back({"sensor", {{"plant/state", InputCounts{5, {}, {}}}}});
  h.undecodable = {{"plant/cmd", 12}, {"sensor/position", 3}};
  h.timing.push_back({"plant", {"cycle", 1001, 0.012, 0.25, 1.5}});
  h.timing.push_back({"estimator_robot1", {"window", 100, 2.5, 7.25, 9.0}});
  h.timing.push_back({"estimator_robot1", {"pf", 100, 3.5, 8.25, 10.0}});
  return h;
}

void expect_same(const HostHealth& a, const HostHealth& b) {
  EXPECT_EQ(a.member, b.member);
  EXPECT_EQ(a.figures.ticks, b.figures.ticks);
  EXPECT_EQ(a.figures.missed_steps, b.figures.missed_steps);
  EXPECT_EQ(a.figures.late_steps, b.figures.late_steps);
  EXPECT_EQ(a.figures.worst_lateness_s, b.figures.worst_lateness_s);
  EXPECT_EQ(a.undecodable, b.undecodable);
  ASSERT_EQ(a.timing.size(), b.timing.size());
  for (std::size_t i = 0; i < a.timing.size(); ++i) {
    EXPECT_EQ(a.timing[i].component, b.timing[i].component);
    EXPECT_EQ(a.timing[i].times.stage, b.timing[i].times.stage);
    EXPECT_EQ(a.timing[i].times.count, b.timing[i].times.count);
    EXPECT_EQ(a.timing[i].times.median_ms, b.timing[i].times.median_ms);
    EXPECT_EQ(a.timing[i].times.p99_ms, b.timing[i].times.p99_ms);
    EXPECT_EQ(a.timing[i].times.max_ms, b.timing[i].times.max_ms);
  }
  ASSERT_EQ(a.components.size(), b.components.size());
  for (std::size_t i = 0; i < a.components.size(); ++i) {
    EXPECT_EQ(a.components[i].component, b.components[i].component);
    ASSERT_EQ(a.components[i].inputs.size(), b.components[i].inputs.size());
    for (std::size_t j = 0; j < a.components[i].inputs.size(); ++j) {
      const InputHealth& x = a.components[i].inputs[j];
      const InputHealth& y = b.components[i].inputs[j];
      EXPECT_EQ(x.topic, y.topic);
      EXPECT_EQ(x.counts.accepted, y.counts.accepted);
      EXPECT_EQ(x.counts.rejected, y.counts.rejected);
      EXPECT_EQ(x.counts.adjusted, y.counts.adjusted);
    }
  }
}

TEST(HealthExchange, ReportRoundTrip) {
  const HostHealth h = sample_health("sim");
  const idl::HostReport report = to_report(h, 77);
  EXPECT_EQ(report.run_id(), 77u);
  expect_same(from_report(report), h);
}

struct Fixture {
  MemoryBus bus;
  Notifier notifier;
  Scenario scenario;
  RunContext run;
  Fixture() {
    scenario.step_s = 0.01;
    run.scenario = &scenario;
    run.bus = &bus;
    run.notifier = &notifier;
    run.mode = TimeMode::kRealtime;
  }
};

TEST(HealthExchange, CollectsTheOthersAndNamesTheSilentOnes) {
  Fixture f;
  HealthExchange sim(f.run, "sim", 5, {});
  HealthExchange other_run(f.run, "sensing", 6, {});  // another run on the domain: ignored
  HealthExchange evaluation(f.run, "evaluation", 5, {"sim", "sensing"});
  RunFigures sim_figures;
  sim_figures.hosts = {sample_health("sim")};
  sim.exchange(sim_figures, 100);
  RunFigures other_figures;
  other_figures.hosts = {sample_health("sensing")};
  other_run.exchange(other_figures, 100);
  RunFigures figures;
  figures.hosts = {sample_health("evaluation")};
  const auto start = std::chrono::steady_clock::now();
  evaluation.exchange(figures, 100, 0.3);
  const double waited_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_EQ(figures.hosts.size(), 2u);
  EXPECT_EQ(figures.hosts[0].member, "evaluation");
  expect_same(figures.hosts[1], sample_health("sim"));
  EXPECT_EQ(figures.hosts_not_heard, std::vector<std::string>{"sensing"});
  EXPECT_GE(waited_s, 0.29);  // bounded: waited for the silent host, then gave up
  EXPECT_LT(waited_s, 2.0);
}

TEST(HealthExchange, ReturnsAsSoonAsEveryoneReported) {
  Fixture f;
  HealthExchange sim(f.run, "sim", 5, {});
  HealthExchange evaluation(f.run, "evaluation", 5, {"sim"});
  RunFigures sim_figures;
  sim_figures.hosts = {sample_health("sim")};
  sim.exchange(sim_figures, 3);
  RunFigures figures;
  figures.hosts = {sample_health("evaluation")};
  const auto start = std::chrono::steady_clock::now();
  evaluation.exchange(figures, 3, 30.0);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);
  EXPECT_EQ(figures.hosts.size(), 2u);
  EXPECT_TRUE(figures.hosts_not_heard.empty());
}

}  // namespace
}  // namespace robodds
