#include "runtime/dds/security_files.hpp"

#include <openssl/bio.h>
#include <openssl/asn1.h>
#include <openssl/err.h>
#include <openssl/evp.h>
#include <openssl/pem.h>
#include <openssl/pkcs7.h>
#include <openssl/x509.h>
#include <openssl/x509_vfy.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <memory>
#include <vector>

#include "runtime/base/error.hpp"

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

struct StoreCtxFree {
  void operator()(X509_STORE_CTX* c) const { X509_STORE_CTX_free(c); }
};
struct SignersFree {
  void operator()(STACK_OF(X509) * s) const { sk_X509_free(s); }  // the certificates belong to the PKCS7
};
struct MdCtxFree {
  void operator()(EVP_MD_CTX* c) const { EVP_MD_CTX_free(c); }
};
struct BytesFree {
  void operator()(unsigned char* p) const { OPENSSL_free(p); }
};

/// OpenSSL's queued errors, oldest first, clearing the queue.
std::vector<unsigned long> take_errors() {
  std::vector<unsigned long> errors;
  while (const unsigned long code = ERR_get_error()) {
    errors.push_back(code);
  }
  return errors;
}

bool has_reason(const std::vector<unsigned long>& errors, int lib, std::initializer_list<int> reasons) {
  for (const unsigned long code : errors) {
    for (const int reason : reasons) {
      if (ERR_GET_LIB(code) == lib && ERR_GET_REASON(code) == reason) {
        return true;
      }
    }
  }
  return false;
}

/// The last (most specific) of `errors` as " (text)", or "".
std::string reason_text(const std::vector<unsigned long>& errors) {
  if (errors.empty()) {
    return "";
  }
  char buffer[256];
  ERR_error_string_n(errors.back(), buffer, sizeof buffer);
  return std::string(" (") + buffer + ")";
}

/// OpenSSL's last error as text (empty if none), clearing the queue.
std::string openssl_reason() { return reason_text(take_errors()); }

/// A distinguished name as "CN=robodds CA plant_smoke" (RFC 2253, as in the permissions).
std::string name_text(const X509_NAME* name) {
  Bio bio(BIO_new(BIO_s_mem()));
  if (!bio || X509_NAME_print_ex(bio.get(), name, 0, XN_FLAG_RFC2253) < 0) {
    ERR_clear_error();
    return "?";
  }
  char* data = nullptr;
  const long size = BIO_get_mem_data(bio.get(), &data);
  return std::string(data, static_cast<std::size_t>(size));
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

const std::string kSignAgain = "run `robodds security init` again, or copy the file again from its output";

/// The signature block (the second MIME part: base64 PKCS#7) cannot be used.
[[noreturn]] void fail_corrupted(const std::string& file, const std::string& kind, const std::string& why) {
  fail(file, kind + " signature block is corrupted: " + why + " (" + kSignAgain + ")");
}

/// SMIME_read_PKCS7 refused the file: not S/MIME at all, its MIME parts broken, or the
/// signature block undecodable (OpenSSL's reason codes, crypto/asn1/asn_mime.c, say which).
[[noreturn]] void fail_unreadable(const std::string& file, const std::string& kind) {
  const std::vector<unsigned long> errors = take_errors();
  const std::string reason = reason_text(errors);
  if (has_reason(errors, ERR_LIB_ASN1, {ASN1_R_ASN1_SIG_PARSE_ERROR, ASN1_R_ASN1_PARSE_ERROR})) {
    fail_corrupted(file, kind, "its base64 PKCS#7 data cannot be decoded" + reason);
  }
  if (has_reason(errors, ERR_LIB_ASN1, {ASN1_R_NO_MULTIPART_BOUNDARY, ASN1_R_NO_MULTIPART_BODY_FAILURE})) {
    fail(file, kind + " S/MIME structure is damaged: the signed content and the signature block are not two parts between its "
                      "boundary lines" + reason + " (" + kSignAgain + ")");
  }
  if (has_reason(errors, ERR_LIB_ASN1, {ASN1_R_MIME_SIG_PARSE_ERROR, ASN1_R_NO_SIG_CONTENT_TYPE, ASN1_R_SIG_INVALID_MIME_TYPE})) {
    fail(file, kind + " S/MIME structure is damaged: its second part is not an application/pkcs7-signature" + reason + " (" +
                   kSignAgain + ")");
  }
  fail(file, kind + " is not an S/MIME signed document: no MIME header 'Content-Type: multipart/signed' (an unsigned copy? "
                    "sign it with the CA: `openssl smime -sign -text ...`, or run `robodds security init` again)" + reason);
}

/// The certificate that signed the document chains to the CA (and nothing else). If not: a
/// self-signed certificate that is intact is another CA's; one whose own signature fails, or that
/// holds the CA's key under another name, was altered inside the signature block.
void check_signer(const std::string& file, const std::string& kind, PKCS7* p7, X509* signer, X509_STORE* store, X509* ca,
                  const std::string& ca_file) {
  std::unique_ptr<X509_STORE_CTX, StoreCtxFree> ctx(X509_STORE_CTX_new());
  if (!ctx || X509_STORE_CTX_init(ctx.get(), store, signer, p7->d.sign->cert) != 1) {
    fail(file, kind + " signature cannot be checked" + openssl_reason());
  }
  X509_STORE_CTX_set_default(ctx.get(), "smime_sign");  // as PKCS7_verify
  if (X509_verify_cert(ctx.get()) == 1) {
    return;
  }
  const std::string why = X509_verify_cert_error_string(X509_STORE_CTX_get_error(ctx.get()));
  ERR_clear_error();
  EVP_PKEY* key = X509_get0_pubkey(signer);
  const bool ca_key = key != nullptr && EVP_PKEY_eq(key, X509_get0_pubkey(ca)) == 1;
  const X509_NAME* subject = X509_get_subject_name(signer);
  const X509_NAME* issuer = X509_get_issuer_name(signer);
  const bool self_issued = X509_NAME_cmp(issuer, subject) == 0;
  const bool self_signed = self_issued && key != nullptr && X509_verify(signer, key) == 1;
  ERR_clear_error();
  if (self_issued && !self_signed) {
    fail_corrupted(file, kind, "the certificate '" + name_text(subject) + "' in it was altered (its own signature does not verify)");
  }
  if (!self_issued && ca_key) {
    fail_corrupted(file, kind, "the certificate '" + name_text(subject) + "' in it was altered (the CA's key under the issuer '" +
                                   name_text(issuer) + "')");
  }
  if (self_signed && !ca_key) {
    const bool same_name = X509_NAME_cmp(subject, X509_get_subject_name(ca)) == 0;
    fail(file, kind + " is signed by another CA: '" + name_text(subject) + "'" + (same_name ? " of the same name but another key" : "") +
                   ", not the CA of " + ca_file + " (signed by another `robodds security init`? deploy the identity folder as one)");
  }
  if (!self_issued && X509_NAME_cmp(issuer, X509_get_subject_name(ca)) != 0) {
    fail(file, kind + " is signed by another CA: its signer '" + name_text(subject) + "' was issued by '" + name_text(issuer) +
                   "', not by the CA of " + ca_file);
  }
  fail(file, kind + " signer '" + name_text(subject) + "' does not verify with the CA of " + ca_file + " (" + why +
                 "): its certificate was altered in the signature block, or issued by another CA of the same name");
}

/// The signer's signature over the signed attributes, which carry the content's digest: checked
/// on its own so that a changed content (digest mismatch) is told from a changed signature.
bool signed_attributes_verify(PKCS7_SIGNER_INFO* info, X509* signer) {
  STACK_OF(X509_ATTRIBUTE)* attributes = PKCS7_get_signed_attributes(info);
  if (attributes == nullptr || sk_X509_ATTRIBUTE_num(attributes) == 0) {
    return true;  // the signature is over the content itself: PKCS7_verify checks it
  }
  const EVP_MD* md = EVP_get_digestbyobj(info->digest_alg->algorithm);
  unsigned char* der = nullptr;
  const int length = ASN1_item_i2d(reinterpret_cast<ASN1_VALUE*>(attributes), &der, ASN1_ITEM_rptr(PKCS7_ATTR_VERIFY));
  std::unique_ptr<unsigned char, BytesFree> der_owner(der);
  std::unique_ptr<EVP_MD_CTX, MdCtxFree> ctx(EVP_MD_CTX_new());
  const bool ok = md != nullptr && length > 0 && ctx && info->enc_digest != nullptr &&
                  EVP_DigestVerifyInit(ctx.get(), nullptr, md, nullptr, X509_get0_pubkey(signer)) == 1 &&
                  EVP_DigestVerify(ctx.get(), info->enc_digest->data, static_cast<std::size_t>(info->enc_digest->length), der,
                                   static_cast<std::size_t>(length)) == 1;
  ERR_clear_error();
  return ok;
}

/// The content of the S/MIME signed document `file` (its lines end in CRLF, as signed), verified
/// with the CA certificate and nothing else. ConfigError naming the file and the kind of damage:
/// not S/MIME, S/MIME structure damaged, signature block corrupted, signed by another CA, content
/// changed after signing.
std::string signed_content(const std::string& file, const std::string& kind, X509* ca, const std::string& ca_file) {
  Bio bio = open_file(file, kind);
  BIO* content = nullptr;
  std::unique_ptr<PKCS7, Pkcs7Free> p7(SMIME_read_PKCS7(bio.get(), &content));
  Bio content_owner(content);
  if (!p7) {
    fail_unreadable(file, kind);
  }
  if (!PKCS7_type_is_signed(p7.get())) {
    ERR_clear_error();
    fail_corrupted(file, kind, "its PKCS#7 data is not a signature");
  }
  if (PKCS7_get_detached(p7.get()) && content == nullptr) {
    fail(file, kind + " S/MIME structure is damaged: a detached signature without the signed content (" + kSignAgain + ")");
  }
  std::unique_ptr<STACK_OF(X509), SignersFree> signers(PKCS7_get0_signers(p7.get(), nullptr, 0));
  STACK_OF(PKCS7_SIGNER_INFO)* infos = PKCS7_get_signer_info(p7.get());
  if (!signers || infos == nullptr || sk_X509_num(signers.get()) != sk_PKCS7_SIGNER_INFO_num(infos) ||
      sk_X509_num(signers.get()) == 0) {
    fail_corrupted(file, kind, "the certificate of its signer is not in it" + openssl_reason());
  }
  std::unique_ptr<X509_STORE, StoreFree> store(X509_STORE_new());
  X509_STORE_add_cert(store.get(), ca);
  for (int i = 0; i < sk_X509_num(signers.get()); ++i) {
    X509* signer = sk_X509_value(signers.get(), i);
    check_signer(file, kind, p7.get(), signer, store.get(), ca, ca_file);
    if (!signed_attributes_verify(sk_PKCS7_SIGNER_INFO_value(infos, i), signer)) {
      fail_corrupted(file, kind, "its signature value does not verify with the key of its signer '" +
                                     name_text(X509_get_subject_name(signer)) + "'");
    }
  }
  Bio out(BIO_new(BIO_s_mem()));
  if (PKCS7_verify(p7.get(), nullptr, store.get(), content, out.get(), PKCS7_TEXT) != 1) {
    const std::vector<unsigned long> errors = take_errors();
    if (has_reason(errors, ERR_LIB_PKCS7, {PKCS7_R_DIGEST_FAILURE})) {
      fail(file, kind + " content was changed after signing: its digest is no longer the one the CA signed (edit the scenario and "
                        "run `robodds security init` again; a signed document cannot be edited)");
    }
    fail_corrupted(file, kind, "it does not verify with the CA of " + ca_file + reason_text(errors));
  }
  char* data = nullptr;
  const long size = BIO_get_mem_data(out.get(), &data);
  return std::string(data, static_cast<std::size_t>(size));
}

/// `text` with CRLF line ends made LF (S/MIME signs text as CRLF lines).
std::string lf_lines(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (!(text[i] == '\r' && i + 1 < text.size() && text[i + 1] == '\n')) {
      out += text[i];
    }
  }
  return out;
}

/// The review copy `robodds security init` writes beside a signed document (permissions.xml),
/// if present, says exactly what was signed (line ends aside): otherwise whoever reads it is
/// misled about what Fast DDS enforces.
void check_review_copy(const fs::path& review, const std::string& signed_file, const std::string& kind, const std::string& signed_text) {
  if (!fs::exists(review)) {
    return;
  }
  std::ifstream in(review, std::ios::binary);
  if (!in) {
    fail(review.string(), "review copy of " + signed_file + " not readable");
  }
  const std::string copy = lf_lines(std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>()));
  const std::string content = lf_lines(signed_text);
  if (copy == content) {
    return;
  }
  const auto mismatch = std::mismatch(copy.begin(), copy.end(), content.begin(), content.end()).first;
  const long line = 1 + std::count(copy.begin(), mismatch, '\n');
  fail(review.string(), "differs from the signed " + kind + " " + signed_file + " at line " + std::to_string(line) +
                            " (Fast DDS enforces the signed one: run `robodds security init` again to change " + kind +
                            ", or delete this copy)");
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
  signed_content(files.governance, "governance", ca.get(), files.identity_ca);
  const std::string permissions = signed_content(files.permissions, "permissions", ca.get(), files.identity_ca);
  check_review_copy(fs::path(files.permissions).parent_path() / "permissions.xml", files.permissions, "permissions", permissions);
  return files;
}

}  // namespace robodds
