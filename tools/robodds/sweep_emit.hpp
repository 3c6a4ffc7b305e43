#pragma once
// `robodds sweep --emit slurm|k8s`: a planned sweep as a batch engine's array job, one array task
// per run, each task `robodds sweep --run-index K --out DIR` (docs/scale.md). Pure text.

#include <cstddef>
#include <string>

namespace robodds::sweep {

/// DDS domains are 0..232: array task K runs on domain (domain offset + K) % kTaskDomains.
constexpr int kTaskDomains = 233;

/// `--domain-offset N`: an integer 0 <= N <= 232 (std::invalid_argument naming the option, the
/// text and the reason otherwise).
int parse_domain_offset(const std::string& text);

/// A Slurm batch script (sbatch) with `--array=0-(runs-1)`; `sweep_dir` is the sweep's folder as
/// the compute nodes see it (a shared file system). The robodds executable is $ROBODDS or robodds.
/// Task K runs on DDS domain (domain_offset + K) % 233 (std::invalid_argument if the offset is
/// not 0..232).
std::string slurm_script(const std::string& sweep_dir, std::size_t runs, int domain_offset = 0);

/// A Kubernetes Indexed Job (batch/v1) of `runs` completions, `parallelism` pods at a time, with
/// `image` (the project's image, deploy/docker) and the sweep's folder on the persistent volume
/// claim `claim`, mounted at /sweep. `name` is the Job's name (a DNS label). The pods run as the
/// image's user (uid and gid 10001) with fsGroup 10001; completion K runs on DDS domain
/// (domain_offset + K) % 233 (std::invalid_argument if the offset is not 0..232).
std::string k8s_job(const std::string& name, std::size_t runs, std::size_t parallelism, const std::string& image,
                    const std::string& claim, int domain_offset = 0);

/// `text` as a DNS-1123 label: lower case, [a-z0-9-], at most 63 characters, not starting or
/// ending with '-' ("sweep" if nothing is left).
std::string dns_label(const std::string& text);

}  // namespace robodds::sweep
