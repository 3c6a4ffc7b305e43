#include "tools/robodds/security_init.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>

#include "runtime/base/error.hpp"
#include "runtime/launch/process_group.hpp"
#include "runtime/base/log.hpp"

namespace robodds {
namespace fs = std::filesystem;
namespace {

constexpr double kOpensslTimeoutS = 60.0;
constexpr int kCannotExecute = 127;  // run_to_exit: the program could not be executed

/// True if `file` is a regular file this process may execute.
bool executable(const fs::path& file) {
  std::error_code error;
  return fs::is_regular_file(file, error) && access(file.c_str(), X_OK) == 0;
}

/// Why the openssl program `program` cannot be run (as execvp would look for it), or "" if it can.
std::string missing_openssl(const std::string& program) {
  if (program.find('/') != std::string::npos) {
    return executable(program) ? ""
                               : "security init: the openssl program " + program +
                                     " was not found or is not executable (install the Debian package openssl)";
  }
  const char* path = std::getenv("PATH");
  const std::string dirs = path != nullptr ? path : "/bin:/usr/bin";  // execvp's default without PATH
  for (std::size_t begin = 0; begin <= dirs.size();) {
    const std::size_t end = std::min(dirs.find(':', begin), dirs.size());
    const std::string dir = dirs.substr(begin, end - begin);
    if (executable(fs::path(dir.empty() ? "." : dir) / program)) {
      return "";
    }
    begin = end + 1;
  }
  return "security init: the '" + program + "' program was not found on PATH (install the Debian package openssl)";
}

void openssl(const SecurityInitOptions& options, const std::string& step, std::vector<std::string> args) {
  args.insert(args.begin(), options.openssl);
  const int code = run_to_exit("openssl (" + step + ")", args, kOpensslTimeoutS);
  if (code != 0) {
    const std::string missing = code == kCannotExecute ? missing_openssl(options.openssl) : "";
    if (!missing.empty()) {
      throw RunError(missing);  // removed while we ran
    }
    std::string line;
    for (const std::string& a : args) {
      line += (line.empty() ? "" : " ") + a;
    }
    const std::string why = code == kCannotExecute ? "the openssl program could not be executed (exit 127)"
                                                   : "openssl exit " + std::to_string(code);
    throw RunError("security init: " + step + " failed (" + why + "): " + line);
  }
}

void write_text(const fs::path& file, const std::string& text) {
  std::ofstream out(file);
  out << text;
  if (!out) {
    throw RunError("security init: cannot write " + file.string());
  }
}

/// ISO 8601 UTC, e.g. 2026-12-02T12:52:00 (the permissions document's validity).
std::string iso_utc(std::time_t t) {
  std::tm tm{};
  gmtime_r(&t, &tm);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%S", &tm);
  return text;
}

/// A new EC P-256 key (ECDSA-SHA256 is one of the two PKI-DH signature algorithms), mode 0600.
void make_key(const SecurityInitOptions& options, const fs::path& key, const std::string& step) {
  openssl(options, step, {"genpkey", "-algorithm", "EC", "-pkeyopt", "ec_paramgen_curve:P-256", "-out", key.string()});
  fs::permissions(key, fs::perms::owner_read | fs::perms::owner_write, fs::perm_options::replace);
}

void sign_document(const SecurityInitOptions& options, const fs::path& ca, const fs::path& in, const fs::path& out) {
  openssl(options, "signing " + in.string(),
          {"smime", "-sign", "-in", in.string(), "-text", "-out", out.string(), "-signer", (ca / "ca_cert.pem").string(),
           "-inkey", (ca / "ca_key.pem").string()});
}

}  // namespace

void security_init(const Scenario& scenario, const std::vector<SecurityIdentity>& identities, const SecurityInitOptions& options) {
  if (options.days < 1) {
    throw ConfigError("--days: expected a whole number of days >= 1, got " + std::to_string(options.days));
  }
  // Before anything is written: openssl is a dependency of the package, but a build tree or a
  // stripped-down image may lack it (a bare "exit 127" said nothing).
  if (const std::string missing = missing_openssl(options.openssl); !missing.empty()) {
    throw RunError(missing);
  }
  const fs::path dir(options.out_dir);
  const fs::path ca = dir / kCaDir;
  const std::string days = std::to_string(options.days);
  fs::create_directories(dir);
  if (options.new_ca || !fs::exists(ca / "ca_key.pem")) {
    fs::create_directories(ca);
    make_key(options, ca / "ca_key.pem", "CA key");
    openssl(options, "CA certificate",
            {"req", "-x509", "-new", "-key", (ca / "ca_key.pem").string(), "-sha256", "-days", days, "-subj",
             "/CN=robodds CA " + scenario.name, "-addext", "basicConstraints=critical,CA:TRUE", "-addext",
             "keyUsage=critical,keyCertSign,cRLSign,digitalSignature", "-out", (ca / "ca_cert.pem").string()});
    log::info("security", "new certificate authority " + (ca / "ca_cert.pem").string());
  } else {
    log::info("security", "re-issuing the identities under the existing CA " + (ca / "ca_cert.pem").string() +
                              " (--new-ca to replace it)");
  }
  write_text(dir / "governance.xml", governance_xml());
  sign_document(options, ca, dir / "governance.xml", dir / "governance.p7s");
  const std::time_t now = std::time(nullptr);
  const std::string not_before = iso_utc(now - 60);  // a minute of clock skew between machines
  const std::string not_after = iso_utc(now + static_cast<std::time_t>(options.days) * 86400);
  for (const SecurityIdentity& identity : identities) {
    const fs::path id_dir = dir / identity.name;
    fs::create_directories(id_dir);
    const std::string cn = common_name(identity.name, scenario.name);
    make_key(options, id_dir / "key.pem", identity.name + " key");
    openssl(options, identity.name + " certificate request",
            {"req", "-new", "-key", (id_dir / "key.pem").string(), "-subj", "/CN=" + cn, "-out", (id_dir / "cert.csr").string()});
    openssl(options, identity.name + " certificate",
            {"x509", "-req", "-in", (id_dir / "cert.csr").string(), "-CA", (ca / "ca_cert.pem").string(), "-CAkey",
             (ca / "ca_key.pem").string(), "-CAcreateserial", "-CAserial", (ca / "serial").string(), "-days", days, "-sha256",
             "-out", (id_dir / "cert.pem").string()});
    fs::remove(id_dir / "cert.csr");
    fs::copy_file(ca / "ca_cert.pem", id_dir / "identity_ca.pem", fs::copy_options::overwrite_existing);
    fs::copy_file(dir / "governance.p7s", id_dir / "governance.p7s", fs::copy_options::overwrite_existing);
    write_text(id_dir / "permissions.xml", permissions_xml(identity, "CN=" + cn, not_before, not_after));
    sign_document(options, ca, id_dir / "permissions.xml", id_dir / "permissions.p7s");
  }
}

}  // namespace robodds
