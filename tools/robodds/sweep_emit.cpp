#include "tools/robodds/sweep_emit.hpp"

#include <algorithm>
#include <cctype>

namespace robodds::sweep {
namespace {

/// `text` in single quotes for sh (an inner ' becomes '\'').
std::string shell_quoted(const std::string& text) {
  std::string out = "'";
  for (const char c : text) {
    out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  }
  return out + "'";
}

// A DDS domain per array task: tasks that share a node (and a network) must not see each other's
// samples. Domains are 0..232; tasks 233 apart on one node at the same time would share one.
constexpr const char* kDomainOfTask = "233";

}  // namespace

std::string slurm_script(const std::string& sweep_dir, std::size_t runs) {
  const std::string dir = shell_quoted(sweep_dir);
  return "#!/bin/bash\n"
         "# robodds sweep as a Slurm job array: one array task per planned run (written by robodds sweep --emit slurm).\n"
         "# Submit where the compute nodes see the sweep folder:  sbatch " + sweep_dir + "/slurm.sbatch\n"
         "# then merge the results:  robodds sweep --aggregate --out " + sweep_dir + "\n"
         "#SBATCH --job-name=robodds-sweep\n"
         "#SBATCH --array=0-" + std::to_string(runs == 0 ? 0 : runs - 1) + "\n"
         "#SBATCH --ntasks=1\n"
         "#SBATCH --cpus-per-task=1\n"
         "#SBATCH --output=\"" + sweep_dir + "/slurm-%a.log\"\n"
         "set -euo pipefail\n"
         "TASK=\"${SLURM_ARRAY_TASK_ID:?not a Slurm array task: submit with sbatch}\"\n"
         "exec \"${ROBODDS:-robodds}\" sweep --run-index \"$TASK\" --out " + dir + " --domain \"$((TASK % " + kDomainOfTask + "))\"\n";
}

std::string k8s_job(const std::string& name, std::size_t runs, std::size_t parallelism, const std::string& image,
                    const std::string& claim) {
  const std::string n = std::to_string(runs);
  return "# robodds sweep as a Kubernetes Indexed Job: one completion per planned run (written by robodds sweep --emit k8s).\n"
         "# The sweep folder (sweep.json, scenario.yaml) must be on the volume claim '" + claim + "', mounted at /sweep.\n"
         "#   kubectl apply -f k8s-job.yaml; kubectl wait --for=condition=complete job/" + name + "\n"
         "# then, with the volume's folder:  robodds sweep --aggregate --out <folder>\n"
         "# A run whose simulation fails is recorded in its folder and its pod succeeds; a pod fails only when\n"
         "# the run could not be carried out (then it is retried, up to backoffLimit).\n"
         "apiVersion: batch/v1\n"
         "kind: Job\n"
         "metadata:\n"
         "  name: " + name + "\n"
         "spec:\n"
         "  completionMode: Indexed\n"
         "  completions: " + n + "\n"
         "  parallelism: " + std::to_string(std::max<std::size_t>(parallelism, 1)) + "\n"
         "  backoffLimit: " + n + "\n"
         "  template:\n"
         "    spec:\n"
         "      restartPolicy: Never\n"
         "      containers:\n"
         "        - name: run\n"
         "          image: \"" + image + "\"\n"
         "          command: [\"/bin/sh\", \"-c\"]\n"
         "          args: [\"exec robodds sweep --run-index \\\"$JOB_COMPLETION_INDEX\\\" --out /sweep --domain "
         "\\\"$((JOB_COMPLETION_INDEX % " + kDomainOfTask + "))\\\"\"]\n"
         "          resources:\n"
         "            requests: {cpu: \"1\"}\n"
         "          volumeMounts:\n"
         "            - {name: sweep, mountPath: /sweep}\n"
         "      volumes:\n"
         "        - name: sweep\n"
         "          persistentVolumeClaim: {claimName: " + claim + "}\n";
}

std::string dns_label(const std::string& text) {
  std::string out;
  for (const char c : text) {
    const char l = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    out += (std::isalnum(static_cast<unsigned char>(l)) != 0) ? l : '-';
  }
  out = out.substr(0, 63);
  const std::size_t first = out.find_first_not_of('-');
  if (first == std::string::npos) {
    return "sweep";
  }
  out = out.substr(first);
  return out.substr(0, out.find_last_not_of('-') + 1);
}

}  // namespace robodds::sweep
