// The start-up checks of DDS Security files (runtime/dds/security_files.hpp) on an identity made
// here with the openssl tool, the way `robodds security init` makes it: each kind of damage to a
// signed document gets its own error naming the file (not S/MIME at all, a damaged S/MIME
// structure, content changed after signing, a corrupted signature block, signed by another CA of
// the same name), and a permissions.xml review copy that differs from the signed permissions is
// refused naming both files.
#include "runtime/dds/security_files.hpp"

#include <gtest/gtest.h>

#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <vector>

#include "runtime/base/error.hpp"

namespace robodds {
namespace {
namespace fs = std::filesystem;

const std::string kPermissions =
    "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    "<dds><permissions><grant name=\"sim\">\n"
    "  <allow_rule><publish><topics><topic>plant/state</topic></topics></publish>\n"
    "  <subscribe><topics><topic>plant/cmd</topic></topics></subscribe></allow_rule>\n"
    "  <default>DENY</default>\n"
    "</grant></permissions></dds>\n";

std::string read(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void write(const fs::path& file, const std::string& text) { std::ofstream(file, std::ios::binary) << text; }

/// Runs the openssl tool (its output goes to DIR/openssl.log); throws if it fails.
void openssl(const fs::path& dir, const std::string& args) {
  const std::string command = "openssl " + args + " >>'" + (dir / "openssl.log").string() + "' 2>&1";
  if (std::system(command.c_str()) != 0) {
    throw std::runtime_error("failed: " + command + "\n" + read(dir / "openssl.log"));
  }
}

std::string quoted(const fs::path& file) { return "'" + file.string() + "'"; }

/// A CA like `robodds security init` makes (EC P-256, CA:TRUE); every CA here has the same name.
struct Ca {
  fs::path key, cert;
};

Ca make_ca(const fs::path& dir) {
  fs::create_directories(dir);
  const Ca ca{dir / "ca_key.pem", dir / "ca_cert.pem"};
  openssl(dir, "genpkey -algorithm EC -pkeyopt ec_paramgen_curve:P-256 -out " + quoted(ca.key));
  openssl(dir, "req -x509 -new -key " + quoted(ca.key) + " -sha256 -days 30 -subj '/CN=robodds CA test'" +
                   " -addext basicConstraints=critical,CA:TRUE -addext keyUsage=critical,keyCertSign,cRLSign,digitalSignature" +
                   " -out " + quoted(ca.cert));
  return ca;
}

void sign(const fs::path& dir, const Ca& ca, const fs::path& in, const fs::path& out) {
  openssl(dir, "smime -sign -in " + quoted(in) + " -text -out " + quoted(out) + " -signer " + quoted(ca.cert) + " -inkey " +
                   quoted(ca.key));
}

/// A security directory DIR/sec with the identity 'sim' (and its permissions.xml review copy),
/// plus DIR/other, a second CA of the same name. Fresh for each test case.
class SecurityFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::path(::testing::TempDir()) / (std::string("security_files.") + info->name());
    fs::remove_all(dir_);
    ca_ = make_ca(dir_ / "sec" / "ca");
    other_ca_ = make_ca(dir_ / "other");
    const fs::path id = dir_ / "sec" / "sim";
    fs::create_directories(id);
    openssl(dir_, "genpkey -algorithm EC -pkeyopt ec_paramgen_curve:P-256 -out " + quoted(id / "key.pem"));
    openssl(dir_, "req -new -key " + quoted(id / "key.pem") + " -subj '/CN=sim@test' -out " + quoted(dir_ / "sim.csr"));
    openssl(dir_, "x509 -req -in " + quoted(dir_ / "sim.csr") + " -CA " + quoted(ca_.cert) + " -CAkey " + quoted(ca_.key) +
                      " -set_serial 2 -days 30 -sha256 -out " + quoted(id / "cert.pem"));
    fs::copy_file(ca_.cert, id / "identity_ca.pem");
    write(dir_ / "governance.xml", "<dds><domain_access_rules/></dds>\n");
    sign(dir_, ca_, dir_ / "governance.xml", id / "governance.p7s");
    write(id / "permissions.xml", kPermissions);
    sign(dir_, ca_, id / "permissions.xml", id / "permissions.p7s");
    permissions_ = id / "permissions.p7s";
    signed_ = read(permissions_);
  }

  /// The ConfigError text of check_security_files(DIR/sec, sim), or "" if it passes.
  std::string check_error() const {
    try {
      check_security_files((dir_ / "sec").string(), "sim");
      return "";
    } catch (const ConfigError& e) {
      return e.what();
    }
  }

  /// check_error() after the signed permissions were replaced by `text`.
  std::string error_with_permissions(const std::string& text) const {
    write(permissions_, text);
    return check_error();
  }

  /// The signed permissions with base64 character `index` of the signature block (from its end
  /// when negative) replaced by `replacement` (0: another valid base64 character).
  std::string with_signature_char(long index, char replacement = 0) const {
    const std::size_t header = signed_.find("filename=\"smime.p7s\"");
    const std::size_t start = signed_.find("\n\n", header) + 2;
    const std::size_t end = signed_.find("\n------", start);
    std::vector<std::size_t> positions;
    for (std::size_t i = start; i < end; ++i) {
      if (std::isalnum(static_cast<unsigned char>(signed_[i])) || signed_[i] == '+' || signed_[i] == '/') {
        positions.push_back(i);
      }
    }
    const std::size_t at = positions.at(index >= 0 ? static_cast<std::size_t>(index) : positions.size() - static_cast<std::size_t>(-index));
    std::string text = signed_;
    text[at] = replacement != 0 ? replacement : (text[at] == 'A' ? 'B' : 'A');
    return text;
  }

  fs::path dir_;
  Ca ca_, other_ca_;
  fs::path permissions_;
  std::string signed_;
};

TEST_F(SecurityFiles, GenuineFilesPassWithOrWithoutAnIdenticalReviewCopy) {
  EXPECT_EQ(check_error(), "");
  fs::remove(dir_ / "sec" / "sim" / "permissions.xml");
  EXPECT_EQ(check_error(), "");
}

TEST_F(SecurityFiles, AFileWithoutMimeStructureIsNotSmime) {
  for (const std::string& text : {kPermissions, std::string(), std::string("hello\n")}) {
    const std::string error = error_with_permissions(text);
    EXPECT_NE(error.find(permissions_.string() + ": DDS Security: permissions is not an S/MIME signed document: no MIME header"),
              std::string::npos)
        << error;
  }
}

TEST_F(SecurityFiles, ADamagedMimeStructureIsNamedAsSuch) {
  std::string text = signed_;
  const std::size_t closing = text.rfind("\n------");
  text.erase(closing);  // the closing boundary line
  const std::string error = error_with_permissions(text);
  EXPECT_NE(error.find(permissions_.string() + ": DDS Security: permissions S/MIME structure is damaged"), std::string::npos)
      << error;
}

TEST_F(SecurityFiles, ContentChangedAfterSigningIsNamedAsSuch) {
  std::string text = signed_;
  text.replace(text.find("plant/cmd"), 9, "sim/clock");
  const std::string error = error_with_permissions(text);
  EXPECT_NE(error.find(permissions_.string() + ": DDS Security: permissions content was changed after signing"), std::string::npos)
      << error;
  const fs::path governance = dir_ / "sec" / "sim" / "governance.p7s";
  std::string governance_text = read(governance);
  governance_text.replace(governance_text.find("domain_access_rules"), 6, "DOMAIN");
  write(permissions_, signed_);
  write(governance, governance_text);
  const std::string governance_error = check_error();
  EXPECT_NE(governance_error.find(governance.string() + ": DDS Security: governance content was changed after signing"),
            std::string::npos)
      << governance_error;
}

TEST_F(SecurityFiles, ACorruptedSignatureBlockIsNamedAsSuch) {
  struct Case {
    const char* what;
    std::string text;
  };
  std::string truncated = signed_;
  truncated.erase(truncated.rfind('\n', truncated.rfind("\n------") - 1) - 60, 60);  // a line of base64 less
  const Case cases[] = {
      {"a character that is not base64", with_signature_char(100, '*')},
      {"the block cut short", truncated},
      {"a byte of the CA certificate's public key", with_signature_char(333)},
      {"a byte of the signature value", with_signature_char(-40)},
  };
  for (const Case& c : cases) {
    const std::string error = error_with_permissions(c.text);
    EXPECT_NE(error.find(permissions_.string() + ": DDS Security: permissions signature block is corrupted"), std::string::npos)
        << c.what << ": " << error;
  }
}

TEST_F(SecurityFiles, ADocumentSignedByAnotherCaOfTheSameNameIsNamedAsSuch) {
  sign(dir_, other_ca_, dir_ / "sec" / "sim" / "permissions.xml", permissions_);
  const std::string error = check_error();
  EXPECT_NE(error.find(permissions_.string() + ": DDS Security: permissions is signed by another CA"), std::string::npos) << error;
  EXPECT_NE(error.find("identity_ca.pem"), std::string::npos) << error;
}

TEST_F(SecurityFiles, AReviewCopyThatDiffersFromTheSignedPermissionsIsRefusedNamingBoth) {
  const fs::path review = dir_ / "sec" / "sim" / "permissions.xml";
  std::string text = kPermissions;
  text.replace(text.find("plant/cmd"), 9, "sim/clock");
  write(review, text);
  const std::string error = check_error();
  EXPECT_NE(error.find(review.string() + ": DDS Security: differs from the signed permissions " + permissions_.string()),
            std::string::npos)
      << error;
  EXPECT_NE(error.find("line 4"), std::string::npos) << error;
  write(review, "");
  EXPECT_NE(check_error().find("differs from the signed permissions"), std::string::npos);
  write(review, kPermissions);
  EXPECT_EQ(check_error(), "");
}

}  // namespace
}  // namespace robodds
