#include "tools/robodds/sweep_emit.hpp"

#include <gtest/gtest.h>

namespace robodds::sweep {
namespace {

TEST(SlurmScript, OneArrayTaskPerRunAndTheFolderQuoted) {
  const std::string s = slurm_script("/data/it's here", 12);
  EXPECT_EQ(s.rfind("#!/bin/bash\n", 0), 0u);
  EXPECT_NE(s.find("#SBATCH --array=0-11\n"), std::string::npos) << s;
  EXPECT_NE(s.find("--run-index \"$TASK\" --out '/data/it'\\''s here' --domain \"$((TASK % 233))\""), std::string::npos) << s;
}

TEST(K8sJob, IndexedJobOfTheRuns) {
  const std::string s = k8s_job("robodds-sweep-x", 40, 4, "robodds:latest", "claim1");
  for (const char* line : {"kind: Job\n", "  completionMode: Indexed\n", "  completions: 40\n", "  parallelism: 4\n",
                           "      restartPolicy: Never\n", "          persistentVolumeClaim: {claimName: claim1}\n",
                           "          image: \"robodds:latest\"\n"}) {
    EXPECT_NE(s.find(line), std::string::npos) << line << "\n" << s;
  }
  EXPECT_NE(s.find("--run-index \\\"$JOB_COMPLETION_INDEX\\\" --out /sweep"), std::string::npos) << s;
}

TEST(DnsLabel, LowerCaseDashesAtMost63) {
  EXPECT_EQ(dns_label("robodds-sweep-Paper1_Results"), "robodds-sweep-paper1-results");
  EXPECT_EQ(dns_label("__"), "sweep");
  EXPECT_EQ(dns_label(std::string(80, 'a')).size(), 63u);
  EXPECT_EQ(dns_label("-a-"), "a");
}

}  // namespace
}  // namespace robodds::sweep
