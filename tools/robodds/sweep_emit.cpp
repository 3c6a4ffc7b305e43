#include "tools/robodds/sweep_emit.hpp"

#include <algorithm>
#include <cctype>
#include <stdexcept>

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
// samples. Domains are 0..232; task K takes (offset + K) % 233, the offset (--domain-offset) keeps
// another sweep on the same nodes off this one's domains.
std::string offset_range() {
  const std::string last = std::to_string(kTaskDomains - 1);
  return "must be 0 to " + last + " (DDS domains are 0-" + last + ")";
}

void check_domain_offset(int offset) {
  if (offset < 0 || offset >= kTaskDomains) {
    throw std::invalid_argument("--domain-offset '" + std::to_string(offset) + "': " + offset_range());
  }
}

/// The shell arithmetic of the task's domain, `task` the variable holding its index.
std::string domain_expression(int offset, const std::string& task) {
  return "$(( (" + std::to_string(offset) + " + " + task + ") % " + std::to_string(kTaskDomains) + " ))";
}

/// Comment lines ("# ...") saying which domains the tasks use and how to keep another sweep off them.
std::string domain_comment(int offset, std::size_t runs) {
  const std::string off = std::to_string(offset);
  const std::string text = "# DDS domain of task K: (" + off + " + K) % " + std::to_string(kTaskDomains) + " (--domain-offset " + off +
                           "; default 0), so tasks on one node do not see each\n"
                           "# other's samples. A sweep that may share nodes with this one (yours or another user's) needs other\n";
  if (runs < static_cast<std::size_t>(kTaskDomains)) {
    return text + "# domains: emit it with --domain-offset " +
           std::to_string((static_cast<std::size_t>(offset) + runs) % kTaskDomains) + " (this offset + " + std::to_string(runs) +
           " runs, mod " + std::to_string(kTaskDomains) + "; docs/scale.md).\n";
  }
  return text + "# domains; this one uses all " + std::to_string(kTaskDomains) + ", so emit it half way round, --domain-offset " +
         std::to_string((offset + kTaskDomains / 2) % kTaskDomains) + " (tasks running at once have close indices; docs/scale.md).\n";
}

}  // namespace

int parse_domain_offset(const std::string& text) {
  const std::size_t sign = !text.empty() && text[0] == '-' ? 1 : 0;
  if (text.size() == sign || text.find_first_not_of("0123456789", sign) != std::string::npos) {
    throw std::invalid_argument("--domain-offset '" + text + "': not an integer (0 to " + std::to_string(kTaskDomains - 1) + ")");
  }
  if (sign == 1 || text.size() > 3 || std::stoi(text) >= kTaskDomains) {
    throw std::invalid_argument("--domain-offset '" + text + "': " + offset_range());
  }
  return std::stoi(text);
}

std::string slurm_script(const std::string& sweep_dir, std::size_t runs, int domain_offset) {
  check_domain_offset(domain_offset);
  const std::string dir = shell_quoted(sweep_dir);
  return "#!/bin/bash\n"
         "# robodds sweep as a Slurm job array: one array task per planned run (written by robodds sweep --emit slurm).\n"
         "# Submit where the compute nodes see the sweep folder:  sbatch " + sweep_dir + "/slurm.sbatch\n"
         "# then merge the results:  robodds sweep --aggregate --out " + sweep_dir + "\n" +
         domain_comment(domain_offset, runs) +
         "#SBATCH --job-name=robodds-sweep\n"
         "#SBATCH --array=0-" + std::to_string(runs == 0 ? 0 : runs - 1) + "\n"
         "#SBATCH --ntasks=1\n"
         "#SBATCH --cpus-per-task=1\n"
         "#SBATCH --output=\"" + sweep_dir + "/slurm-%a.log\"\n"
         "set -euo pipefail\n"
         "TASK=\"${SLURM_ARRAY_TASK_ID:?not a Slurm array task: submit with sbatch}\"\n"
         "exec \"${ROBODDS:-robodds}\" sweep --run-index \"$TASK\" --out " + dir + " --domain \"" + domain_expression(domain_offset, "TASK") + "\"\n";
}

std::string k8s_job(const std::string& name, std::size_t runs, std::size_t parallelism, const std::string& image,
                    const std::string& claim, int domain_offset) {
  check_domain_offset(domain_offset);
  const std::string n = std::to_string(runs);
  return "# robodds sweep as a Kubernetes Indexed Job: one completion per planned run (written by robodds sweep --emit k8s).\n"
         "# The sweep folder (sweep.json, scenario.yaml) must be on the volume claim '" + claim + "', mounted at /sweep.\n"
         "#   kubectl apply -f k8s-job.yaml; kubectl wait --for=condition=complete job/" + name + "\n"
         "# then, with the volume's folder:  robodds sweep --aggregate --out <folder>\n"
         "# A run whose simulation fails is recorded in its folder and its pod succeeds; a pod fails only when\n"
         "# the run could not be carried out (then it is retried, up to backoffLimit).\n" +
         domain_comment(domain_offset, runs) +
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
         "      # as the image's user robodds (uid, gid 10001); fsGroup makes the claim's volume writable by it\n"
         "      securityContext:\n"
         "        runAsUser: 10001\n"
         "        runAsGroup: 10001\n"
         "        fsGroup: 10001\n"
         "      containers:\n"
         "        - name: run\n"
         "          image: \"" + image + "\"\n"
         "          command: [\"/bin/sh\", \"-c\"]\n"
         "          args: [\"exec robodds sweep --run-index \\\"$JOB_COMPLETION_INDEX\\\" --out /sweep --domain "
         "\\\"" + domain_expression(domain_offset, "JOB_COMPLETION_INDEX") + "\\\"\"]\n"
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
