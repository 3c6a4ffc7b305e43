// `robodds security init` (tools/robodds/security_init.hpp) with the real openssl tool, checked by
// the start-up checks (runtime/dds/security_files.hpp): every identity it makes passes; a
// tampered document, a certificate of another CA and a missing file are refused naming the file;
// a second init keeps the CA (rotation), --new-ca replaces it (revocation); its permissions.xml
// review copy is what was signed (an edited one is refused); without the openssl program the
// error names it and its Debian package.
#include "tools/robodds/security_init.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "runtime/dds/security_files.hpp"
#include "runtime/base/error.hpp"

namespace robodds {
namespace {
namespace fs = std::filesystem;

std::string read(const fs::path& file) {
  std::ifstream in(file);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void write(const fs::path& file, const std::string& text) { std::ofstream(file) << text; }

/// A fresh directory owned by the running test case.
fs::path case_dir() {
  const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir = fs::path(::testing::TempDir()) / (std::string("security_init.") + info->name());
  fs::remove_all(dir);
  return dir;
}

Scenario tiny_scenario() {
  Scenario scenario;
  scenario.file = "tiny.yaml";
  scenario.name = "tiny";
  scenario.groups.push_back(GroupSpec{"sim", {}});
  return scenario;
}

std::vector<SecurityIdentity> identities() {
  return {SecurityIdentity{"sim", {"plant/state"}, {"plant/cmd"}}, SecurityIdentity{"tools", {}, {"plant/state"}}};
}

/// The ConfigError text of check_security_files(dir, identity), or "" if it passes.
std::string check_error(const fs::path& dir, const std::string& identity) {
  try {
    check_security_files(dir.string(), identity);
    return "";
  } catch (const ConfigError& e) {
    return e.what();
  }
}

void init(const fs::path& dir, bool new_ca = false) {
  SecurityInitOptions options;
  options.out_dir = dir.string();
  options.new_ca = new_ca;
  security_init(tiny_scenario(), identities(), options);
}

TEST(SecurityInit, EveryIdentityPassesTheStartUpChecks) {
  const fs::path dir = case_dir();
  init(dir);
  EXPECT_EQ(check_error(dir, "sim"), "");
  EXPECT_EQ(check_error(dir, "tools"), "");
  EXPECT_EQ(fs::status(dir / "sim" / "key.pem").permissions() & fs::perms::all, fs::perms::owner_read | fs::perms::owner_write);
  EXPECT_NE(read(dir / "sim" / "permissions.p7s").find("<topic>plant/state</topic>"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "sim" / "ca_key.pem"));  // the CA key stays in DIR/ca
}

TEST(SecurityInit, TamperedMissingAndForeignFilesAreRefusedNamingTheFile) {
  const fs::path dir = case_dir();
  init(dir);
  const fs::path permissions = dir / "sim" / "permissions.p7s";
  const std::string signed_text = read(permissions);
  std::string tampered = signed_text;
  tampered.replace(tampered.find("plant/cmd"), 9, "sim/clock");
  write(permissions, tampered);
  {
    const std::string error = check_error(dir, "sim");
    EXPECT_NE(error.find(permissions.string() + ": DDS Security: permissions content was changed after signing"), std::string::npos)
        << error;
  }
  write(permissions, signed_text);
  EXPECT_EQ(check_error(dir, "sim"), "");
  fs::remove(dir / "sim" / "governance.p7s");
  EXPECT_NE(check_error(dir, "sim").find("governance.p7s: DDS Security: governance not found"), std::string::npos);
  EXPECT_NE(check_error(dir, "nobody").find("no identity 'nobody'"), std::string::npos);

  const fs::path other = dir.string() + ".other";
  fs::remove_all(other);
  init(other);
  fs::copy_file(other / "sim" / "cert.pem", dir / "sim" / "cert.pem", fs::copy_options::overwrite_existing);
  EXPECT_NE(check_error(dir, "sim").find("cert.pem: DDS Security: identity certificate is not signed by the CA"),
            std::string::npos);
}

TEST(SecurityInit, ItsPermissionsXmlIsTheSignedContentAndAnEditedOneIsRefused) {
  const fs::path dir = case_dir();
  init(dir);
  const fs::path review = dir / "sim" / "permissions.xml";
  std::string text = read(review);
  text.replace(text.find("plant/cmd"), 9, "sim/clock");
  write(review, text);
  const std::string error = check_error(dir, "sim");
  EXPECT_NE(error.find(review.string() + ": DDS Security: differs from the signed permissions " + (dir / "sim" / "permissions.p7s").string()),
            std::string::npos)
      << error;
}

/// Runs `body` with the environment variable PATH set to `path`, then restores it.
template <typename Body>
void with_path(const std::string& path, Body body) {
  const char* old = std::getenv("PATH");
  const std::string saved = old != nullptr ? old : "";
  setenv("PATH", path.c_str(), 1);
  try {
    body();
  } catch (...) {
    setenv("PATH", saved.c_str(), 1);
    throw;
  }
  setenv("PATH", saved.c_str(), 1);
}

/// The RunError text of security_init with `options` (out_dir set here), or "" if it succeeds.
std::string init_error(const fs::path& dir, SecurityInitOptions options) {
  options.out_dir = dir.string();
  try {
    security_init(tiny_scenario(), identities(), options);
    return "";
  } catch (const RunError& e) {
    return e.what();
  }
}

TEST(SecurityInit, WithoutTheOpensslProgramTheErrorNamesItAndItsDebianPackage) {
  const fs::path dir = case_dir();
  const fs::path empty_bin = dir.string() + ".bin";
  fs::create_directories(empty_bin);
  std::string error;
  with_path(empty_bin.string(), [&] { error = init_error(dir, SecurityInitOptions{}); });
  EXPECT_NE(error.find("security init: the 'openssl' program was not found on PATH (install the Debian package openssl)"),
            std::string::npos)
      << error;
  EXPECT_FALSE(fs::exists(dir / "ca")) << "nothing is written before openssl is found";
  SecurityInitOptions options;
  options.openssl = (empty_bin / "openssl").string();
  error = init_error(dir, options);
  EXPECT_NE(error.find("security init: the openssl program " + options.openssl + " was not found or is not executable"),
            std::string::npos)
      << error;
}

TEST(SecurityInit, ASecondInitKeepsTheCaAndNewCaReplacesIt) {
  const fs::path dir = case_dir();
  init(dir);
  const std::string ca = read(dir / "ca" / "ca_cert.pem");
  const std::string old_cert = read(dir / "sim" / "cert.pem");
  init(dir);  // rotation: new keys and certificates, same CA
  EXPECT_EQ(read(dir / "ca" / "ca_cert.pem"), ca);
  EXPECT_NE(read(dir / "sim" / "cert.pem"), old_cert);
  EXPECT_EQ(check_error(dir, "sim"), "");
  init(dir, true);  // revocation: a new CA; the old certificate is no longer trusted
  EXPECT_NE(read(dir / "ca" / "ca_cert.pem"), ca);
  write(dir / "sim" / "cert.pem", old_cert);
  EXPECT_NE(check_error(dir, "sim").find("not signed by the CA"), std::string::npos);
}

}  // namespace
}  // namespace robodds
