#include "runtime/launch/host_digest.hpp"

#include <filesystem>

#include "common/number_text.hpp"
#include "runtime/dds/file_digest.hpp"
#include "runtime/dds/security_files.hpp"

namespace robodds {

RunDigest host_digest(const Scenario& scenario, const std::string& params_file, const std::vector<std::string>& sets,
                      const DdsOptions& dds) {
  const auto name_of = [](const std::string& path) { return std::filesystem::path(path).filename().string(); };
  RunDigest digest;
  digest.push_back(DigestEntry{"scenario", scenario.file, sha256_of_file(scenario.file)});
  // The effective seed and duration: `robodds run` gives its children both, a host by hand may
  // take them from the scenario; the same run either way.
  std::string options = "seed=" + std::to_string(scenario.seed) + " duration_s=" + shortest_text(scenario.duration_s);
  for (const std::string& set : sets) {
    options += " --set " + set;
  }
  digest.push_back(DigestEntry{"options", options, sha256_hex(options)});
  if (!params_file.empty()) {
    digest.push_back(DigestEntry{digest_label("params", name_of(params_file)), params_file, sha256_of_file(params_file)});
  }
  for (const std::string& file : dds.qos_files) {
    digest.push_back(DigestEntry{digest_label("qos", name_of(file)), file, sha256_of_file(file)});
  }
  if (!dds.security_dir.empty()) {
    // One governance for the run; the identity's own files (certificate, key, permissions) differ by design.
    const std::string governance = security_files(dds.security_dir, dds.security_identity.empty() ? kCoordinatorIdentity
                                                                                                   : dds.security_identity)
                                       .governance;
    if (std::filesystem::is_regular_file(governance)) {  // else the DDS Security check names it, with the reason
      digest.push_back(DigestEntry{digest_label("governance", name_of(governance)), governance, sha256_of_file(governance)});
    }
  }
  return digest;
}

}  // namespace robodds
