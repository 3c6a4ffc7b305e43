#include "tools/robodds/sweep_emit.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <stdexcept>
#include <utility>

namespace robodds::sweep {
namespace {

/// The first line `shell -c command` prints.
std::string shell_output(const std::string& shell, const std::string& command) {
  std::string out;
  if (FILE* p = popen((shell + " -c '" + command + "'").c_str(), "r")) {
    char line[64] = {};
    if (fgets(line, sizeof line, p) != nullptr) {
      out = line;
    }
    pclose(p);
  }
  return out;
}

/// The `$(( ... ))` of the task's domain in an emitted script.
std::string domain_argument(const std::string& script) {
  const std::size_t at = script.find("$((");
  return at == std::string::npos ? "" : script.substr(at, script.find("))", at) + 2 - at);
}

TEST(SlurmScript, OneArrayTaskPerRunAndTheFolderQuoted) {
  const std::string s = slurm_script("/data/it's here", 12);
  EXPECT_EQ(s.rfind("#!/bin/bash\n", 0), 0u);
  EXPECT_NE(s.find("#SBATCH --array=0-11\n"), std::string::npos) << s;
  EXPECT_NE(s.find("--run-index \"$TASK\" --out '/data/it'\\''s here' --domain \"$(( (0 + TASK) % 233 ))\""), std::string::npos) << s;
}

// Issue 22: two sweeps on one node took the same domains (TASK % 233); --domain-offset N moves them.
TEST(SlurmScript, DomainOffsetMovesEveryTaskAndTheCommentSaysTheNextOffset) {
  const std::string s = slurm_script("/data/sw2", 12, 100);
  EXPECT_NE(s.find("--out '/data/sw2' --domain \"$(( (100 + TASK) % 233 ))\"\n"), std::string::npos) << s;
  EXPECT_NE(s.find("# DDS domain of task K: (100 + K) % 233 (--domain-offset 100; default 0)"), std::string::npos) << s;
  EXPECT_NE(s.find("emit it with --domain-offset 112 (this offset + 12 runs, mod 233"), std::string::npos) << s;
  EXPECT_NE(slurm_script("/d", 40, 200).find("--domain-offset 7 (this offset + 40 runs, mod 233"), std::string::npos);  // wraps
  EXPECT_NE(slurm_script("/d", 500, 10).find("this one uses all 233, so emit it half way round, --domain-offset 126"),
            std::string::npos);
  // The comment lines come before the #SBATCH directives (sbatch stops reading them at the first command).
  EXPECT_LT(s.find("# DDS domain"), s.find("#SBATCH"));
  EXPECT_THROW(slurm_script("/d", 1, 233), std::invalid_argument);
  EXPECT_THROW(slurm_script("/d", 1, -1), std::invalid_argument);
}

TEST(SlurmScript, TheTaskDomainArithmeticInTheShell) {
  // What the shells make of the emitted expressions: task 5 of offset 230 is domain 2.
  EXPECT_EQ(shell_output("bash", "TASK=5; echo " + domain_argument(slurm_script("/d", 12, 230))), "2\n");
  EXPECT_EQ(shell_output("sh", "JOB_COMPLETION_INDEX=5; echo " + domain_argument(k8s_job("x", 12, 1, "i", "c", 230))), "2\n");
  EXPECT_EQ(shell_output("bash", "TASK=232; echo " + domain_argument(slurm_script("/d", 240, 0))), "232\n");
}

TEST(ParseDomainOffset, ZeroTo232) {
  EXPECT_EQ(parse_domain_offset("0"), 0);
  EXPECT_EQ(parse_domain_offset("17"), 17);
  EXPECT_EQ(parse_domain_offset("232"), 232);
  EXPECT_EQ(parse_domain_offset("007"), 7);
}

TEST(ParseDomainOffset, BadTextNamesTheOptionAndTheReason) {
  const std::pair<const char*, const char*> cases[] = {
      {"233", "--domain-offset '233': must be 0 to 232 (DDS domains are 0-232)"},
      {"-1", "--domain-offset '-1': must be 0 to 232"},
      {"99999999999999999999", "--domain-offset '99999999999999999999': must be 0 to 232"},
      {"", "--domain-offset '': not an integer (0 to 232)"},
      {"x", "--domain-offset 'x': not an integer"},
      {"1.5", "--domain-offset '1.5': not an integer"},
      {" 3", "--domain-offset ' 3': not an integer"},
      {"-", "--domain-offset '-': not an integer"},
      {"+4", "--domain-offset '+4': not an integer"},
  };
  for (const auto& [text, message] : cases) {
    try {
      parse_domain_offset(text);
      ADD_FAILURE() << "accepted '" << text << "'";
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()).rfind(message, 0), 0u) << e.what();
    }
  }
}

TEST(K8sJob, IndexedJobOfTheRuns) {
  const std::string s = k8s_job("robodds-sweep-x", 40, 4, "robodds:latest", "claim1");
  for (const char* line : {"kind: Job\n", "  completionMode: Indexed\n", "  completions: 40\n", "  parallelism: 4\n",
                           "      restartPolicy: Never\n", "          persistentVolumeClaim: {claimName: claim1}\n",
                           "          image: \"robodds:latest\"\n"}) {
    EXPECT_NE(s.find(line), std::string::npos) << line << "\n" << s;
  }
  EXPECT_NE(s.find("--run-index \\\"$JOB_COMPLETION_INDEX\\\" --out /sweep --domain \\\"$(( (0 + JOB_COMPLETION_INDEX) % 233 ))\\\"\"]\n"),
            std::string::npos) << s;
}

TEST(K8sJob, DomainOffsetMovesEveryCompletion) {
  const std::string s = k8s_job("robodds-sweep-x", 40, 4, "robodds:latest", "claim1", 50);
  EXPECT_NE(s.find("--domain \\\"$(( (50 + JOB_COMPLETION_INDEX) % 233 ))\\\"\"]\n"), std::string::npos) << s;
  EXPECT_NE(s.find("# DDS domain of task K: (50 + K) % 233 (--domain-offset 50; default 0)"), std::string::npos) << s;
  EXPECT_NE(s.find("emit it with --domain-offset 90 (this offset + 40 runs"), std::string::npos) << s;
  EXPECT_THROW(k8s_job("x", 1, 1, "i", "c", 233), std::invalid_argument);
}

// Issue 22: the image runs as robodds (uid, gid 10001); without fsGroup it may not write the claim.
TEST(K8sJob, PodRunsAsTheImageUserWithFsGroup) {
  const std::string s = k8s_job("robodds-sweep-x", 3, 1, "robodds:latest", "claim1");
  const std::string pod_security = "    spec:\n"
                                   "      restartPolicy: Never\n"
                                   "      # as the image's user robodds (uid, gid 10001); fsGroup makes the claim's volume writable by it\n"
                                   "      securityContext:\n"
                                   "        runAsUser: 10001\n"
                                   "        runAsGroup: 10001\n"
                                   "        fsGroup: 10001\n"
                                   "      containers:\n";
  EXPECT_NE(s.find(pod_security), std::string::npos) << s;  // pod level (6 spaces), not in the container
}

TEST(DnsLabel, LowerCaseDashesAtMost63) {
  EXPECT_EQ(dns_label("robodds-sweep-Paper1_Results"), "robodds-sweep-paper1-results");
  EXPECT_EQ(dns_label("__"), "sweep");
  EXPECT_EQ(dns_label(std::string(80, 'a')).size(), 63u);
  EXPECT_EQ(dns_label("-a-"), "a");
}

}  // namespace
}  // namespace robodds::sweep
