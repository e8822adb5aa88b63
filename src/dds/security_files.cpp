#include "litamin2/dds/security_files.hpp"

#include <openssl/bio.h>
#include <openssl/err.h>
#include <openssl/pem.h>
#include <openssl/pkcs7.h>
#include <openssl/x509.h>
#include <openssl/x509_vfy.h>

#include <cctype>
#include <ctime>
#include <filesystem>
#include <memory>
#include <string_view>
#include <vector>

namespace litamin2::dds {

namespace {

struct Free {
  void operator()(BIO* p) const { BIO_free_all(p); }
  void operator()(X509* p) const { X509_free(p); }
  void operator()(EVP_PKEY* p) const { EVP_PKEY_free(p); }
  void operator()(PKCS7* p) const { PKCS7_free(p); }
  void operator()(X509_STORE* p) const { X509_STORE_free(p); }
  void operator()(X509_STORE_CTX* p) const { X509_STORE_CTX_free(p); }
};
template <class T>
using Owned = std::unique_ptr<T, Free>;

/// The oldest pending OpenSSL error, for messages; clears the queue.
std::string openssl_error() {
  const unsigned long code = ERR_get_error();
  char text[256] = "no detail";
  if (code != 0) ERR_error_string_n(code, text, sizeof(text));
  ERR_clear_error();
  return text;
}

std::string bio_text(BIO* bio) {
  char* data = nullptr;
  const long size = BIO_get_mem_data(bio, &data);
  return size > 0 ? std::string(data, static_cast<std::size_t>(size)) : std::string();
}

std::string time_text(const ASN1_TIME* time) {
  Owned<BIO> bio(BIO_new(BIO_s_mem()));
  ASN1_TIME_print(bio.get(), time);
  return bio_text(bio.get());
}

/// "YYYY-MM-DDTHH:MM:SS" of the current UTC time: the format of permission grants' validity.
std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char text[32];
  std::strftime(text, sizeof(text), "%Y-%m-%dT%H:%M:%S", &tm);
  return text;
}

std::string trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return std::string(s);
}

/// The contents of every <tag>...</tag> (or <tag attr="...">...</tag>) of `xml`, in order.
std::vector<std::string_view> elements(std::string_view xml, const std::string& tag) {
  std::vector<std::string_view> out;
  const std::string open = "<" + tag, close = "</" + tag + ">";
  std::size_t pos = 0;
  while ((pos = xml.find(open, pos)) != std::string_view::npos) {
    const std::size_t after = pos + open.size();
    if (after >= xml.size() || (xml[after] != '>' && xml[after] != ' ')) {
      pos = after;
      continue;
    }
    const std::size_t start = xml.find('>', after);
    const std::size_t end = start == std::string_view::npos ? start : xml.find(close, start);
    if (end == std::string_view::npos) break;
    out.push_back(xml.substr(start + 1, end - start - 1));
    pos = end + close.size();
  }
  return out;
}

std::string first(std::string_view xml, const std::string& tag) {
  const auto found = elements(xml, tag);
  return found.empty() ? std::string() : trim(found.front());
}

/// Whether a <domains> element (ids and id ranges) holds `domain`.
bool domains_cover(std::string_view domains, int domain) {
  for (std::string_view id : elements(domains, "id"))
    if (trim(id) == std::to_string(domain)) return true;
  for (std::string_view range : elements(domains, "id_range")) {
    const std::string lo = first(range, "min"), hi = first(range, "max");
    try {
      if ((lo.empty() || std::stol(lo) <= domain) && (hi.empty() || domain <= std::stol(hi)))
        return true;
    } catch (const std::exception&) {
    }
  }
  return false;
}

/// The RDNs of a distinguished name, trimmed, in order ("CN=a, O=b" -> {"CN=a", "O=b"}): how
/// DDS-Security compares a grant's subject_name with the certificate's RFC 2253 subject.
std::vector<std::string> rdns(std::string_view name) {
  std::vector<std::string> out;
  std::size_t start = 0;
  for (std::size_t i = 0; i <= name.size(); ++i) {
    if (i == name.size() || name[i] == ',') {
      out.push_back(trim(name.substr(start, i - start)));
      start = i + 1;
    }
  }
  return out;
}

class Checker {
 public:
  Checker(const service::SecurityConfig& config, int domain) : c_(config), domain_(domain) {}

  std::optional<std::string> run() {
    Owned<X509> identity_ca, certificate, permissions_ca;
    if (auto why = certificate_file("identity_ca", c_.identity_ca, identity_ca)) return why;
    if (auto why = certificate_file("certificate", c_.certificate, certificate)) return why;
    if (auto why = issued_by(certificate.get(), identity_ca.get())) return why;
    if (auto why = private_key(certificate.get())) return why;
    if (auto why = certificate_file("permissions_ca", c_.permissions_ca, permissions_ca))
      return why;
    std::string governance, permissions;
    if (auto why = signed_document("governance", c_.governance, permissions_ca.get(), governance))
      return why;
    if (auto why =
            signed_document("permissions", c_.permissions, permissions_ca.get(), permissions))
      return why;
    if (auto why = governance_covers_domain(governance)) return why;
    return grant_for(certificate.get(), permissions);
  }

 private:
  std::string where(const char* key, const std::string& path) const {
    return std::string("security.") + key + ": '" + path + "'";
  }

  std::optional<std::string> certificate_file(const char* key, const std::string& path,
                                              Owned<X509>& out) {
    Owned<BIO> bio(BIO_new_file(path.c_str(), "r"));
    if (!bio) return where(key, path) + " cannot be opened";
    out.reset(PEM_read_bio_X509(bio.get(), nullptr, nullptr, nullptr));
    if (!out) return where(key, path) + " is not a PEM certificate (" + openssl_error() + ")";
    if (X509_cmp_current_time(X509_get0_notAfter(out.get())) < 0)
      return where(key, path) + " expired on " + time_text(X509_get0_notAfter(out.get()));
    if (X509_cmp_current_time(X509_get0_notBefore(out.get())) > 0)
      return where(key, path) + " is not valid before " + time_text(X509_get0_notBefore(out.get()));
    return std::nullopt;
  }

  /// A store that trusts `ca` only.
  static Owned<X509_STORE> trusting(X509* ca) {
    Owned<X509_STORE> store(X509_STORE_new());
    X509_STORE_add_cert(store.get(), ca);
    return store;
  }

  std::optional<std::string> issued_by(X509* certificate, X509* ca) {
    Owned<X509_STORE> store = trusting(ca);
    Owned<X509_STORE_CTX> ctx(X509_STORE_CTX_new());
    X509_STORE_CTX_init(ctx.get(), store.get(), certificate, nullptr);
    if (X509_verify_cert(ctx.get()) == 1) return std::nullopt;
    const std::string reason = X509_verify_cert_error_string(X509_STORE_CTX_get_error(ctx.get()));
    ERR_clear_error();
    return where("certificate", c_.certificate) + " is not issued by security.identity_ca '" +
           c_.identity_ca + "' (" + reason + ")";
  }

  std::optional<std::string> private_key(X509* certificate) {
    Owned<BIO> bio(BIO_new_file(c_.private_key.c_str(), "r"));
    if (!bio) return where("private_key", c_.private_key) + " cannot be opened";
    Owned<EVP_PKEY> key(PEM_read_bio_PrivateKey(bio.get(), nullptr, nullptr, nullptr));
    if (!key)
      return where("private_key", c_.private_key) + " is not an unencrypted PEM private key (" +
             openssl_error() + ")";
    if (X509_check_private_key(certificate, key.get()) != 1) {
      ERR_clear_error();
      return where("private_key", c_.private_key) + " does not match security.certificate '" +
             c_.certificate + "'";
    }
    return std::nullopt;
  }

  /// Verifies an S/MIME document against the permissions CA and returns its content.
  std::optional<std::string> signed_document(const char* key, const std::string& path, X509* ca,
                                             std::string& content) {
    Owned<BIO> bio(BIO_new_file(path.c_str(), "r"));
    if (!bio) return where(key, path) + " cannot be opened";
    BIO* signed_content = nullptr;
    Owned<PKCS7> p7(SMIME_read_PKCS7(bio.get(), &signed_content));
    Owned<BIO> data(signed_content);
    if (!p7)
      return where(key, path) +
             " is not an S/MIME signed document (sign it with the permissions CA, as "
             "scripts/litamin2-pki does)";
    Owned<X509_STORE> store = trusting(ca);
    Owned<BIO> out(BIO_new(BIO_s_mem()));
    if (PKCS7_verify(p7.get(), nullptr, store.get(), data.get(), out.get(), PKCS7_TEXT) != 1)
      return where(key, path) +
             ": its signature does not verify against security.permissions_ca '" +
             c_.permissions_ca + "' (tampered with, or signed by another CA: " + openssl_error() +
             ")";
    content = bio_text(out.get());
    return std::nullopt;
  }

  std::optional<std::string> governance_covers_domain(const std::string& governance) {
    for (std::string_view rule : elements(governance, "domain_rule"))
      for (std::string_view domains : elements(rule, "domains"))
        if (domains_cover(domains, domain_)) return std::nullopt;
    return where("governance", c_.governance) + " has no domain rule for DDS domain " +
           std::to_string(domain_);
  }

  std::optional<std::string> grant_for(X509* certificate, const std::string& permissions) {
    Owned<BIO> bio(BIO_new(BIO_s_mem()));
    X509_NAME_print_ex(bio.get(), X509_get_subject_name(certificate), 0,
                       XN_FLAG_RFC2253 & ~ASN1_STRFLGS_ESC_MSB);
    const std::string subject = bio_text(bio.get());
    const std::string now = utc_now();
    std::string found;
    for (std::string_view grant : elements(permissions, "grant")) {
      if (rdns(first(grant, "subject_name")) != rdns(subject)) continue;
      const std::string not_before = first(grant, "not_before"),
                        not_after = first(grant, "not_after");
      if (now < not_before) {
        found = " is not valid before " + not_before + " (UTC)";
        continue;
      }
      if (not_after < now) {
        found = " expired on " + not_after + " (UTC)";
        continue;
      }
      for (std::string_view domains : elements(grant, "domains"))
        if (domains_cover(domains, domain_)) return std::nullopt;
      found = " does not cover DDS domain " + std::to_string(domain_);
    }
    if (!found.empty())
      return where("permissions", c_.permissions) + ": the grant for '" + subject + "'" + found;
    return where("permissions", c_.permissions) + " has no grant for the certificate's subject '" +
           subject + "' (the permissions of another participant?)";
  }

  const service::SecurityConfig& c_;
  const int domain_;
};

}  // namespace

std::optional<std::string> security_files_error(const service::SecurityConfig& config, int domain) {
  if (!config.enabled) return std::nullopt;
  if (auto why = service::security_config_error(config)) return why;
  return Checker(config, domain).run();
}

void add_security_properties(const service::SecurityConfig& config,
                             eprosima::fastdds::dds::DomainParticipantQos& qos) {
  if (!config.enabled) return;
  auto& p = qos.properties().properties();
  const auto file = [](const std::string& path) {
    return "file://" + std::filesystem::absolute(path).string();
  };
  const std::string auth = "dds.sec.auth.builtin.PKI-DH.";
  const std::string access = "dds.sec.access.builtin.Access-Permissions.";
  p.emplace_back("dds.sec.auth.plugin", "builtin.PKI-DH");
  p.emplace_back(auth + "identity_ca", file(config.identity_ca));
  p.emplace_back(auth + "identity_certificate", file(config.certificate));
  p.emplace_back(auth + "private_key", file(config.private_key));
  p.emplace_back("dds.sec.access.plugin", "builtin.Access-Permissions");
  p.emplace_back(access + "permissions_ca", file(config.permissions_ca));
  p.emplace_back(access + "governance", file(config.governance));
  p.emplace_back(access + "permissions", file(config.permissions));
  p.emplace_back("dds.sec.crypto.plugin", "builtin.AES-GCM-GMAC");
}

}  // namespace litamin2::dds
