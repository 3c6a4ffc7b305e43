// idl_schema_text(): every topic type of the catalog has a schema that holds its struct and every
// struct and enum it uses (read from idl/robodds.idl itself), inside the modules robodds::idl.
#include "idl/idl_schema.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "runtime/topics/topic_catalog.hpp"

namespace robodds {
namespace {

/// Short name of a type, e.g. RobotState of robodds::idl::RobotState.
std::string short_name(const std::string& qualified) { return qualified.substr(qualified.rfind(':') + 1); }

/// The bodies of every struct of the IDL file, by name; the names of its enums.
struct IdlFile {
  std::map<std::string, std::string> struct_bodies;
  std::set<std::string> enums;
};

IdlFile read_idl() {
  std::ifstream in(std::string(ROBODDS_SOURCE_DIR) + "/idl/robodds.idl");
  std::stringstream text;
  text << in.rdbuf();
  std::string idl = std::regex_replace(text.str(), std::regex("//[^\n]*"), "");
  IdlFile file;
  const std::regex structs("struct\\s+(\\w+)\\s*\\{([^}]*)\\}");
  for (std::sregex_iterator it(idl.begin(), idl.end(), structs), end; it != end; ++it) {
    file.struct_bodies[(*it)[1]] = (*it)[2];
  }
  const std::regex enums("enum\\s+(\\w+)");
  for (std::sregex_iterator it(idl.begin(), idl.end(), enums), end; it != end; ++it) {
    file.enums.insert((*it)[1]);
  }
  return file;
}

/// Every struct and enum `name` uses, transitively, itself included.
void uses(const IdlFile& file, const std::string& name, std::set<std::string>& out) {
  if (!out.insert(name).second || file.struct_bodies.count(name) == 0) {
    return;
  }
  const std::string& body = file.struct_bodies.at(name);
  const std::regex word("\\w+");
  for (std::sregex_iterator it(body.begin(), body.end(), word), end; it != end; ++it) {
    const std::string w = it->str();
    if (file.struct_bodies.count(w) != 0 || file.enums.count(w) != 0) {
      uses(file, w, out);
    }
  }
}

TEST(IdlSchema, EveryCatalogTypeHasItsStructAndEveryTypeItUses) {
  const IdlFile file = read_idl();
  ASSERT_GT(file.struct_bodies.size(), 10u) << "idl/robodds.idl read";
  ASSERT_FALSE(topic_catalog().empty());
  for (const TopicInfo& topic : topic_catalog()) {
    const std::string text = idl_schema_text(topic.type_name);
    ASSERT_FALSE(text.empty()) << topic.name << ": no schema for " << topic.type_name;
    EXPECT_EQ(text.rfind("module robodds {\n  module idl {\n", 0), 0u) << topic.type_name << ":\n" << text;
    std::set<std::string> needed;
    uses(file, short_name(topic.type_name), needed);
    for (const std::string& name : needed) {
      const std::string declaration = (file.enums.count(name) != 0 ? "enum " : "struct ") + name + " {";
      EXPECT_NE(text.find(declaration), std::string::npos)
          << topic.name << " (" << topic.type_name << ") needs " << name << ":\n" << text;
    }
    EXPECT_EQ(text.find("//"), std::string::npos) << "comments dropped";
  }
}

TEST(IdlSchema, AStructIsDefinedAfterWhatItUsesAndOnlyWhatItNeedsIsIn) {
  const std::string text = idl_schema_text("robodds::idl::WaypointMission");
  const auto waypoint = text.find("struct Waypoint {");
  const auto mission = text.find("struct WaypointMission {");
  ASSERT_NE(waypoint, std::string::npos);
  ASSERT_NE(mission, std::string::npos);
  EXPECT_LT(waypoint, mission);
  EXPECT_NE(text.find("@key unsigned long robot_id;"), std::string::npos) << "annotations kept";
  EXPECT_EQ(text.find("RobotState"), std::string::npos) << "no type it does not use";
}

TEST(IdlSchema, AnUnknownTypeHasNoneAndTheSchemaNameIsTheQualifiedName) {
  EXPECT_EQ(idl_schema_text("robodds::idl::NoSuchType"), "");
  EXPECT_EQ(idl_schema_name("robodds::idl::RobotState"), "robodds::idl::RobotState");
}

}  // namespace
}  // namespace robodds
