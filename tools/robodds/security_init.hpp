#pragma once
// `robodds security init`: the certificate authority, the identities and the signed documents of
// a scenario's secure deployment, made by the `openssl` tool (no cryptography of our own).
//
// DIR/ca/ca_key.pem, ca_cert.pem   the CA (its key never leaves this folder: keep it offline)
// DIR/governance.xml, .p7s         the governance (unsigned for review, and signed)
// DIR/<identity>/                  everything one participant needs, and nothing of any other:
//   identity_ca.pem                the CA certificate (identity CA and permissions CA)
//   cert.pem, key.pem              its certificate (CN=<identity>@<scenario>) and private key (0600)
//   governance.p7s                 the governance, S/MIME signed by the CA
//   permissions.xml, .p7s          its permissions (the .xml for review), signed by the CA

#include <map>
#include <string>
#include <vector>

#include "runtime/config/scenario.hpp"
#include "tools/robodds/security_policy.hpp"

namespace robodds {

struct SecurityInitOptions {
  std::string out_dir;
  int days = 365;          // validity of the certificates and permissions (days from now)
  bool new_ca = false;     // replace an existing CA (revokes every identity it signed)
  std::string openssl = "openssl";
};

/// Makes (or, when DIR/ca exists and !new_ca, re-issues under the same CA) every identity of
/// `identities`. RunError naming the openssl step that failed, or, before anything is written,
/// saying that the openssl program is not found (on PATH) and which Debian package has it;
/// ConfigError on bad options.
void security_init(const Scenario& scenario, const std::vector<SecurityIdentity>& identities, const SecurityInitOptions& options);

}  // namespace robodds
