#include "runtime/launch/host_args.hpp"

#include <gtest/gtest.h>

#include <CLI/CLI.hpp>

#include <functional>
#include <limits>

#include "runtime/base/error.hpp"

namespace robodds {
namespace {

/// Parses `argv` (the arguments after `robodds host`) the way `robodds host` does.
HostArgs parse(const std::vector<std::string>& argv) {
  HostArgs args;
  CLI::App app;
  add_host_options(&app, args);
  std::vector<const char*> raw = {"host"};
  for (const std::string& a : argv) {
    raw.push_back(a.c_str());
  }
  app.parse(static_cast<int>(raw.size()), raw.data());
  return args;
}

HostArgs every_field_set() {
  HostArgs a;
  a.scenario = "sim/scenarios/paper1_ideal.yaml";
  a.group = "estimator";
  a.components = {"plant", "position_sensor"};
  a.params = "/tmp/over rides.yaml";  // a space: one argv element, no quoting
  a.sets = {"controller.epsilon_m=0.01", "evaluator.topics=[a, b]"};
  a.member = "m1";
  a.coordinate = true;
  a.members = {"sim", "estimator"};
  a.run_id = std::numeric_limits<std::uint64_t>::max();
  a.out = "out/x";
  a.deploy = "processes";
  a.realtime = true;
  a.epoch_ns = 1764633600123456789LL;
  a.duration_s = 0.1 + 0.2;  // not a short decimal: must survive the text round trip exactly
  a.seed = 0;                // given, although 0
  a.log_level = "debug";
  a.max_missed_steps = 0;    // given, although 0
  a.rt_priority = 99;
  a.dds.domain = 102;
  a.dds.qos_files = {"a.xml", "b.xml"};
  a.dds.participant_profile = "robodds.participant.udp_only";
  a.dds.security_dir = "sec/plant_smoke";
  a.dds.discovery_servers = "10.0.0.7:11811,backup.lan:11812";
  a.lockstep.input_timeout_s = 2.5;
  a.lockstep.start_timeout_s = 1.0 / 3.0;
  a.lockstep.lockstep_window = 8;
  a.type = "pf_estimator";
  a.name = "estimator";
  a.robots = {"1", "2:50,10,0.5"};
  a.step_s = 0.1 + 0.7;  // not a short decimal either
  return a;
}

TEST(HostArgs, RenderThenParseGivesTheSameStruct) {
  const HostArgs original = every_field_set();
  const HostArgs parsed = parse(to_argv(original));
  EXPECT_TRUE(parsed == original);
  // Field by field, so that a failure names the field (and operator== cannot hide one).
  EXPECT_EQ(parsed.scenario, original.scenario);
  EXPECT_EQ(parsed.components, original.components);
  EXPECT_EQ(parsed.params, original.params);
  EXPECT_EQ(parsed.members, original.members);
  EXPECT_EQ(parsed.robots, original.robots);
  EXPECT_EQ(parsed.step_s, original.step_s);
  EXPECT_EQ(parsed.type, original.type);
  EXPECT_EQ(parsed.run_id, original.run_id);
  EXPECT_EQ(parsed.deploy, original.deploy);
  EXPECT_EQ(parsed.epoch_ns, original.epoch_ns);
  EXPECT_EQ(parsed.duration_s, original.duration_s);
  EXPECT_EQ(parsed.seed, original.seed);
  EXPECT_EQ(parsed.log_level, original.log_level);
  EXPECT_EQ(parsed.max_missed_steps, original.max_missed_steps);
  EXPECT_EQ(parsed.rt_priority, original.rt_priority);
  EXPECT_TRUE(parsed.dds == original.dds);
  EXPECT_EQ(parsed.lockstep.start_timeout_s, original.lockstep.start_timeout_s);
  EXPECT_EQ(parsed.lockstep.lockstep_window, original.lockstep.lockstep_window);
}

TEST(HostArgs, EachFieldAloneSurvivesTheRoundTrip) {
  // A field that to_argv forgets, or that operator== ignores, shows up here as a difference
  // from the default after the round trip.
  const HostArgs full = every_field_set();
  const std::vector<std::function<void(HostArgs&)>> set_one = {
      [&](HostArgs& a) { a.scenario = full.scenario; },   [&](HostArgs& a) { a.group = full.group; },
      [&](HostArgs& a) { a.components = full.components; }, [&](HostArgs& a) { a.params = full.params; },
      [&](HostArgs& a) { a.member = full.member; },       [&](HostArgs& a) { a.coordinate = true; },
      [&](HostArgs& a) { a.members = full.members; },     [&](HostArgs& a) { a.run_id = 7; },
      [&](HostArgs& a) { a.out = full.out; },             [&](HostArgs& a) { a.deploy = full.deploy; },
      [&](HostArgs& a) { a.realtime = true; },            [&](HostArgs& a) { a.epoch_ns = full.epoch_ns; },
      [&](HostArgs& a) { a.duration_s = full.duration_s; }, [&](HostArgs& a) { a.seed = 5; },
      [&](HostArgs& a) { a.log_level = "warn"; },         [&](HostArgs& a) { a.dds.domain = 0; },
      [&](HostArgs& a) { a.dds.qos_files = {"q.xml"}; },  [&](HostArgs& a) { a.dds.participant_profile = "p"; },
      [&](HostArgs& a) { a.lockstep.input_timeout_s = 3; }, [&](HostArgs& a) { a.lockstep.start_timeout_s = 4; },
      [&](HostArgs& a) { a.lockstep.lockstep_window = 2; }, [&](HostArgs& a) { a.max_missed_steps = 3; },
      [&](HostArgs& a) { a.rt_priority = 1; },
      [&](HostArgs& a) { a.dds.security_dir = full.dds.security_dir; },
      [&](HostArgs& a) { a.dds.discovery_servers = full.dds.discovery_servers; },
  };
  for (std::size_t i = 0; i < set_one.size(); ++i) {
    HostArgs one;
    set_one[i](one);
    EXPECT_FALSE(one == HostArgs{}) << "field " << i << " is not compared";
    const std::vector<std::string> argv = to_argv(one);
    EXPECT_FALSE(argv.empty()) << "field " << i << " is not rendered";
    EXPECT_TRUE(parse(argv) == one) << "field " << i << " does not survive: " << ::testing::PrintToString(argv);
  }
}

TEST(HostArgs, DefaultsRenderNothing) {
  EXPECT_TRUE(to_argv(HostArgs{}).empty());
  EXPECT_TRUE(parse({}) == HostArgs{});
}

TEST(HostArgs, FixedOrderAndPlaceholders) {
  HostArgs a;
  a.scenario = "/opt/robodds/s.yaml";
  a.group = "sim";
  a.out = "/opt/robodds/out/s";
  const ArgPlaceholders run_id = {{"--run-id", "${ROBODDS_RUN_ID:-1}"}};
  // A placeholder is written even for a default value (compose needs the variable).
  EXPECT_EQ(to_argv(a, run_id), (std::vector<std::string>{"--scenario", "/opt/robodds/s.yaml", "--group", "sim", "--run-id",
                                                           "${ROBODDS_RUN_ID:-1}", "--out", "/opt/robodds/out/s"}));
  HostArgs coordinator;
  coordinator.scenario = "s.yaml";
  coordinator.coordinate = true;
  EXPECT_EQ(to_argv(coordinator, run_id),
            (std::vector<std::string>{"--scenario", "s.yaml", "--coordinate", "--run-id", "${ROBODDS_RUN_ID:-1}"}));
}

TEST(HostArgs, ParserRequiresNothingByItself) {
  HostArgs args;
  CLI::App app;
  const HostArgOptions options = add_host_options(&app, args);
  const char* argv[] = {"host", "--coordinate"};
  EXPECT_NO_THROW(app.parse(2, argv));
  ASSERT_NE(options.scenario, nullptr);
  EXPECT_FALSE(options.scenario->get_required());
}

TEST(HostArgs, ParserChecksRanges) {
  EXPECT_THROW(parse({"--domain", "233"}), CLI::ValidationError);
  EXPECT_THROW(parse({"--lockstep-window", "0"}), CLI::ValidationError);
  EXPECT_THROW(parse({"--duration", "0"}), CLI::ValidationError);
}

TEST(HostArgs, DurationAndStepRejectNanInfinityAndNegatives) {
  for (const char* option : {"--duration", "--step"}) {
    for (const char* bad : {"nan", "NaN", "inf", "-inf", "-1", "0", "1e400", "2s"}) {
      EXPECT_THROW(parse({option, bad}), CLI::ValidationError) << option << " " << bad;
    }
  }
  try {
    parse({"--duration", "nan"});
  } catch (const CLI::ValidationError& e) {
    EXPECT_EQ(std::string(e.what()), "--duration: must be a positive, finite number of seconds (got nan)");
  }
  // Positive and finite passes; whether it fits the step is checked with the scenario (checked_last_step()).
  EXPECT_EQ(parse({"--duration", "1e300"}).duration_s, 1e300);
  EXPECT_EQ(parse({"--step", "1e-25"}).step_s, 1e-25);
}

TEST(HostArgs, SeedIsAWholeNumberThatFits) {
  for (const char* bad : {"-1", "18446744073709551616", "99999999999999999999999", "1.5", "1e3", "+1", " 1", ""}) {
    EXPECT_THROW(parse({"--seed", bad}), CLI::ParseError) << bad;
  }
  try {
    parse({"--seed", "-1"});
  } catch (const CLI::ValidationError& e) {
    EXPECT_EQ(std::string(e.what()), "--seed: must be a whole number 0..18446744073709551615 (got -1)");
  }
  EXPECT_EQ(parse({"--seed", "18446744073709551615"}).seed, std::numeric_limits<std::uint64_t>::max());
  EXPECT_EQ(parse({"--seed", "0"}).seed, 0u);
}

TEST(HostArgs, MaxMissedStepsIsAWholeNumber) {
  EXPECT_FALSE(parse({}).max_missed_steps);
  EXPECT_EQ(parse({"--max-missed-steps", "0"}).max_missed_steps, 0u);
  EXPECT_EQ(parse({"--max-missed-steps", "25"}).max_missed_steps, 25u);
  for (const char* bad : {"-1", "nan", "1.5", ""}) {
    EXPECT_THROW(parse({"--max-missed-steps", bad}), CLI::ParseError) << bad;
  }
}

TEST(HostArgs, RtPriorityIsOneTo99) {
  EXPECT_FALSE(parse({}).rt_priority);
  EXPECT_EQ(parse({"--rt-priority", "1"}).rt_priority, 1);
  EXPECT_EQ(parse({"--rt-priority", "99"}).rt_priority, 99);
  for (const char* bad : {"0", "100", "-1", "50.5", "nan", "", " 5", "1e1"}) {
    EXPECT_THROW(parse({"--rt-priority", bad}), CLI::ParseError) << bad;
  }
  try {
    parse({"--rt-priority", "0"});
    ADD_FAILURE() << "--rt-priority 0 was accepted";
  } catch (const CLI::ValidationError& e) {
    EXPECT_EQ(std::string(e.what()),
              "--rt-priority: must be a whole number 1..99 (the SCHED_FIFO priority; 99 is the highest) (got 0)");
  }
}

TEST(DiscoveryServers, ParsesAddressesPortsAndBackupsInOrder) {
  const auto servers = parse_discovery_servers("10.0.0.7,discovery:11812;127.0.0.1:1");
  ASSERT_EQ(servers.size(), 3u);
  EXPECT_EQ(servers[0].host, "10.0.0.7");
  EXPECT_EQ(servers[0].port, 11811) << "the default port";
  EXPECT_EQ(servers[1].host, "discovery");
  EXPECT_EQ(servers[1].port, 11812);
  EXPECT_EQ(servers[2].port, 1);
  EXPECT_TRUE(parse_discovery_servers("").empty()) << "none: the profile's discovery";
  EXPECT_EQ(discovery_servers_text(servers), "10.0.0.7:11811,discovery:11812,127.0.0.1:1");
  EXPECT_EQ(discovery_servers_text(parse_discovery_servers(discovery_servers_text(servers))), discovery_servers_text(servers));
}

TEST(DiscoveryServers, BadEntriesAreRefusedNamingTheOptionAndTheEntry) {
  const auto error_of = [](const std::string& text) {
    try {
      parse_discovery_servers(text);
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(error_of("10.0.0.7:0").find("--discovery-server '10.0.0.7:0': '10.0.0.7:0' has no valid port (1-65535)"), std::string::npos)
      << error_of("10.0.0.7:0");
  EXPECT_NE(error_of("10.0.0.7:65536").find("no valid port"), std::string::npos);
  EXPECT_NE(error_of("10.0.0.7:x1").find("no valid port"), std::string::npos);
  EXPECT_NE(error_of(":11811").find("has no address"), std::string::npos);
  EXPECT_NE(error_of("a,,b").find("'' has no address"), std::string::npos) << error_of("a,,b");
  EXPECT_NE(error_of("a,").find("has no address"), std::string::npos);
  EXPECT_NE(error_of("my host:1").find("space"), std::string::npos);
  std::string many;
  for (int i = 0; i < 256; ++i) {
    many += (i ? "," : "") + std::string("h");
  }
  EXPECT_NE(error_of(many).find("at most 255"), std::string::npos);
}

}  // namespace
}  // namespace robodds
