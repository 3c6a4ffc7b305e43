#pragma once
// DDS Security policy of a scenario (`robodds security init`): which identities exist and which
// topics each may publish and subscribe to, and the governance and permissions XML documents
// (OMG DDS Security 1.1 schema, as Fast DDS 2.9's builtin.Access-Permissions reads it). Pure:
// text in, text out; the signing and the keys are security_init.cpp's (the openssl tool).

#include <map>
#include <set>
#include <string>
#include <vector>

#include "runtime/dds/security_files.hpp"
#include "runtime/host/producer_check.hpp"
#include "runtime/config/scenario.hpp"

namespace robodds {

/// The CA's folder under the security directory (its key: never deployed). The identity names
/// (kCoordinatorIdentity, ...) are runtime/dds/security_files.hpp's.
inline constexpr const char* kCaDir = "ca";

struct SecurityIdentity {
  std::string name;                  // folder name under the security directory and certificate CN
  std::set<std::string> publishes;   // topic names it may write
  std::set<std::string> subscribes;  // topic names it may read
};

/// One identity per group (the topics its components write and read, plus the lockstep and health
/// protocol a host of that group uses), the coordinator, the co-located run and the tools. Topics
/// of `component_topics` come from scenario_component_topics() (union over both time modes).
/// ConfigError naming the scenario file if a group is named like a reserved identity.
std::vector<SecurityIdentity> security_identities(const Scenario& scenario,
                                                  const std::map<std::string, ComponentTopics>& component_topics);

/// The governance document: every domain, unauthenticated participants refused, join and
/// read/write access control on every topic, payloads encrypted (AES-GCM); discovery, liveliness
/// and submessage metadata unprotected (why: the document's comment).
std::string governance_xml();

/// The permissions document of one identity: its subject name, validity (ISO 8601 UTC, e.g.
/// "2026-12-02T12:00:00"), the topics it may publish and subscribe to on every domain, and
/// DENY for everything else.
std::string permissions_xml(const SecurityIdentity& identity, const std::string& subject_name, const std::string& not_before,
                            const std::string& not_after);

/// The certificate subject of an identity: one common name "<identity>@<scenario>" (one RDN, so
/// the permissions document's "CN=..." and openssl's "/CN=..." cannot differ in order).
std::string common_name(const std::string& identity, const std::string& scenario_name);

}  // namespace robodds
