#pragma once
// The DDS Security files of one participant (`--security DIR`, identity = a folder of DIR made by
// `robodds security init`), checked with libcrypto before Fast DDS sees them: Fast DDS only logs
// why it refuses a certificate or a document and then fails to create the participant.
// Fast-DDS-free: the launcher checks every identity of a run before it spawns anything.

#include <string>

namespace robodds {

/// Identities that are not deployment groups (`robodds security init` makes them; a group may not
/// take these names). A host's identity is its group.
inline constexpr const char* kCoordinatorIdentity = "coordinator";  // `robodds run --deploy processes`, `robodds host --coordinate`
inline constexpr const char* kColocatedIdentity = "colocated";      // `robodds run` (one process: every group and the coordinator)
inline constexpr const char* kToolsIdentity = "tools";              // `robodds topics` and `robodds echo` (read only)

/// The files of `identity` under `dir` (the names `robodds security init` writes).
struct SecurityFiles {
  std::string identity_ca;   // CA certificate (identity CA and permissions CA)
  std::string certificate;   // this participant's certificate
  std::string private_key;   // its private key
  std::string governance;    // S/MIME signed governance
  std::string permissions;   // S/MIME signed permissions
};
SecurityFiles security_files(const std::string& dir, const std::string& identity);

/// ConfigError naming the file and what is wrong: missing or unreadable, not PEM, certificate
/// expired or not yet valid, not signed by the CA, key not the certificate's; for the signed
/// documents (governance, permissions), which kind of damage: not S/MIME at all, S/MIME structure
/// damaged, content changed after signing, signature block corrupted, signed by another CA; and
/// a permissions.xml review copy beside permissions.p7s that differs from what was signed
/// (naming both files; no review copy is fine). Returns the files.
SecurityFiles check_security_files(const std::string& dir, const std::string& identity);

}  // namespace robodds
