#include "runtime/dds/security_files.hpp"

#include <openssl/bio.h>
#include <openssl/err.h>
#include <openssl/evp.h>
#include <openssl/pem.h>
#include <openssl/pkcs7.h>
#include <openssl/x509.h>
#include <openssl/x509_vfy.h>

#include <filesystem>
#include <fstream>
#include <memory>

#include "runtime/error.hpp"

namespace robodds {
namespace fs = std::filesystem;
namespace {

struct BioFree {
  void operator()(BIO* b) const { BIO_free_all(b); }
};
struct X509Free {
  void operator()(X509* x) const { X509_free(x); }
};
struct KeyFree {
  void operator()(EVP_PKEY* k) const { EVP_PKEY_free(k); }
};
struct Pkcs7Free {
  void operator()(PKCS7* p) const { PKCS7_free(p); }
};
struct StoreFree {
  void operator()(X509_STORE* s) const { X509_STORE_free(s); }
};
using Bio = std::unique_ptr<BIO, BioFree>;
using Cert = std::unique_ptr<X509, X509Free>;

/// OpenSSL's last error as text (empty if none), clearing the queue.
std::string openssl_reason() {
  std::string text;
  while (const unsigned long code = ERR_get_error()) {
    char buffer[256];
    ERR_error_string_n(code, buffer, sizeof buffer);
    text = buffer;  // the last one is the most specific
  }
  return text.empty() ? "" : " (" + text + ")";
}

[[noreturn]] void fail(const std::string& file, const std::string& what) {
  throw ConfigError(located(file, "", "DDS Security: " + what));
}

Bio open_file(const std::string& file, const std::string& kind) {
  if (!fs::exists(file)) {
    fail(file, kind + " not found (made by `robodds security init SCENARIO --out DIR`; --security names DIR)");
  }
  Bio bio(BIO_new_file(file.c_str(), "r"));
  if (!bio) {
    fail(file, kind + " not readable" + openssl_reason());
  }
  return bio;
}

Cert read_certificate(const std::string& file, const std::string& kind) {
  Bio bio = open_file(file, kind);
  Cert cert(PEM_read_bio_X509(bio.get(), nullptr, nullptr, nullptr));
  if (!cert) {
    fail(file, kind + " is not a PEM X.509 certificate" + openssl_reason());
  }
  return cert;
}

void check_validity(const X509* cert, const std::string& file, const std::string& kind) {
  if (X509_cmp_current_time(X509_get0_notAfter(cert)) <= 0) {
    fail(file, kind + " has expired: issue a new one (`robodds security init` again; docs/security.md, rotating)");
  }
  if (X509_cmp_current_time(X509_get0_notBefore(cert)) >= 0) {
    fail(file, kind + " is not valid yet (is this machine's clock right?)");
  }
}

/// The document's S/MIME signature verifies with the CA certificate (and nothing else).
void check_signed(const std::string& file, const std::string& kind, X509* ca, const std::string& ca_file) {
  Bio bio = open_file(file, kind);
  BIO* content = nullptr;
  std::unique_ptr<PKCS7, Pkcs7Free> p7(SMIME_read_PKCS7(bio.get(), &content));
  Bio content_owner(content);
  if (!p7) {
    fail(file, kind + " is not an S/MIME signed document (sign it with the CA: `openssl smime -sign -text ...`, or run "
                      "`robodds security init` again)" + openssl_reason());
  }
  std::unique_ptr<X509_STORE, StoreFree> store(X509_STORE_new());
  X509_STORE_add_cert(store.get(), ca);
  Bio out(BIO_new(BIO_s_mem()));
  if (PKCS7_verify(p7.get(), nullptr, store.get(), content, out.get(), PKCS7_TEXT) != 1) {
    fail(file, kind + " signature does not verify with the CA " + ca_file +
                   ": it was changed after signing, or signed by another CA" + openssl_reason());
  }
}

}  // namespace

SecurityFiles security_files(const std::string& dir, const std::string& identity) {
  const fs::path base = fs::absolute(fs::path(dir) / identity);
  return SecurityFiles{(base / "identity_ca.pem").string(), (base / "cert.pem").string(), (base / "key.pem").string(),
                       (base / "governance.p7s").string(), (base / "permissions.p7s").string()};
}

SecurityFiles check_security_files(const std::string& dir, const std::string& identity) {
  if (!fs::is_directory(dir)) {
    fail(dir, "security directory not found (make it with `robodds security init SCENARIO --out " + dir + "`)");
  }
  const fs::path identity_dir = fs::path(dir) / identity;
  if (!fs::is_directory(identity_dir)) {
    fail(identity_dir.string(), "no identity '" + identity + "' in " + dir +
                                    " (made for another scenario? `robodds security init` makes one per group and tool)");
  }
  const SecurityFiles files = security_files(dir, identity);
  Cert ca = read_certificate(files.identity_ca, "CA certificate");
  check_validity(ca.get(), files.identity_ca, "CA certificate");
  Cert cert = read_certificate(files.certificate, "identity certificate");
  check_validity(cert.get(), files.certificate, "identity certificate");
  {
    std::unique_ptr<EVP_PKEY, KeyFree> ca_key(X509_get_pubkey(ca.get()));
    if (!ca_key || X509_verify(cert.get(), ca_key.get()) != 1) {
      ERR_clear_error();
      fail(files.certificate, "identity certificate is not signed by the CA " + files.identity_ca +
                                  " (from another `robodds security init`? deploy the folder as one)");
    }
  }
  {
    Bio bio = open_file(files.private_key, "private key");
    std::unique_ptr<EVP_PKEY, KeyFree> key(PEM_read_bio_PrivateKey(bio.get(), nullptr, nullptr, nullptr));
    if (!key) {
      fail(files.private_key, "private key is not a PEM key (or is encrypted)" + openssl_reason());
    }
    if (X509_check_private_key(cert.get(), key.get()) != 1) {
      ERR_clear_error();
      fail(files.private_key, "private key does not belong to the certificate " + files.certificate);
    }
  }
  check_signed(files.governance, "governance", ca.get(), files.identity_ca);
  check_signed(files.permissions, "permissions", ca.get(), files.identity_ca);
  return files;
}

}  // namespace robodds
