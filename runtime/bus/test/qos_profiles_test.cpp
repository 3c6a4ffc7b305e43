// The profile-name constants of runtime/bus/qos_profiles.hpp against the XML files that define them.
// A plain text scan (no Fast DDS): every `<KIND profile_name="NAME"` outside XML comments.

#include "runtime/bus/qos_profiles.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <regex>
#include <set>
#include <string>
#include <utility>

#include "runtime/topics/topic_catalog.hpp"

namespace robodds {
namespace {

using ProfileSet = std::set<std::pair<std::string, std::string>>;  // (element, profile name)

std::string read_source_file(const std::string& relative) {
  const std::string path = std::string(ROBODDS_SOURCE_DIR) + "/" + relative;
  std::ifstream in(path);
  EXPECT_TRUE(in.good()) << "cannot read " << path;
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::string without_xml_comments(std::string text) {
  for (std::size_t begin = text.find("<!--"); begin != std::string::npos; begin = text.find("<!--", begin)) {
    const std::size_t end = text.find("-->", begin);
    text.erase(begin, end == std::string::npos ? std::string::npos : end + 3 - begin);
  }
  return text;
}

ProfileSet profiles_in(const std::string& xml) {
  static const std::regex element(R"re(<\s*(participant|data_writer|data_reader)\s[^>]*profile_name\s*=\s*"([^"]*)")re");
  ProfileSet found;
  const std::string text = without_xml_comments(xml);
  for (auto it = std::sregex_iterator(text.begin(), text.end(), element); it != std::sregex_iterator(); ++it) {
    found.emplace((*it)[1].str(), (*it)[2].str());
  }
  return found;
}

TEST(QosProfilesXml, ScanFindsElementsAndSkipsComments) {
  const ProfileSet found = profiles_in(
      "<profiles>\n<!-- <data_writer profile_name=\"old\"> -->\n"
      "<participant profile_name=\"p\" is_default_profile=\"true\">\n<data_reader profile_name=\"r\">\n</profiles>");
  EXPECT_EQ(found, (ProfileSet{{"participant", "p"}, {"data_reader", "r"}}));
}

TEST(QosProfilesXml, EveryDataProfileIsAWriterAndAReaderInRoboddsQosXml) {
  const std::string file = "deploy/qos/robodds_qos.xml";
  const ProfileSet found = profiles_in(read_source_file(file));
  ASSERT_FALSE(data_profile_names().empty());
  for (const std::string& name : data_profile_names()) {
    EXPECT_TRUE(found.count({"data_writer", name})) << file << " has no <data_writer profile_name=\"" << name << "\">";
    EXPECT_TRUE(found.count({"data_reader", name})) << file << " has no <data_reader profile_name=\"" << name << "\">";
  }
}

TEST(QosProfilesXml, EveryParticipantProfileIsInTheQosFiles) {
  ProfileSet found = profiles_in(read_source_file("deploy/qos/robodds_qos.xml"));
  found.merge(profiles_in(read_source_file("deploy/qos/discovery_client.xml")));
  for (const std::string& name : participant_profile_names()) {
    EXPECT_TRUE(found.count({"participant", name}))
        << "no <participant profile_name=\"" << name << "\"> in deploy/qos/robodds_qos.xml or discovery_client.xml";
  }
}

TEST(QosProfiles, EveryQosClassNamesADataProfile) {
  for (QosClass qos_class : {QosClass::kSensor, QosClass::kState, QosClass::kCommand, QosClass::kMission, QosClass::kLockstep}) {
    EXPECT_THAT(data_profile_names(), testing::Contains(std::string(to_string(qos_class))));
  }
}

TEST(QosProfiles, EveryProfileTheCatalogPicksIsADataProfile) {
  for (const TopicInfo& topic : topic_catalog()) {
    for (TimeMode mode : {TimeMode::kLockstep, TimeMode::kRealtime}) {
      for (bool single_process : {false, true}) {
        EXPECT_THAT(data_profile_names(), testing::Contains(qos_profile_for(topic, mode, single_process))) << topic.name;
      }
    }
    EXPECT_THAT(data_profile_names(), testing::Contains(monitor_profile_for(topic))) << topic.name;
  }
}

TEST(QosProfiles, LockstepSubstitutesEveryClassButMission) {
  const TopicInfo& mission = topic_info("mission/waypoints");
  const TopicInfo& sensor = topic_info("sensor/position");
  EXPECT_EQ(qos_profile_for(mission, TimeMode::kLockstep, false), kMissionProfile);
  EXPECT_EQ(qos_profile_for(sensor, TimeMode::kLockstep, false), kLockstepProfile);
  EXPECT_EQ(qos_profile_for(sensor, TimeMode::kLockstep, true), kLockstepLocalProfile);
  EXPECT_EQ(qos_profile_for(sensor, TimeMode::kRealtime, true), kSensorProfile);
  EXPECT_EQ(monitor_profile_for(mission), kMissionProfile);
  EXPECT_EQ(monitor_profile_for(sensor), kMonitorProfile);
}

TEST(QosProfiles, RequiredProfilesAreTheParticipantThenEveryDataProfileAsWriterAndReader) {
  const std::vector<QosProfileRef> required = required_profiles("p");
  ASSERT_EQ(required.size(), 1 + 2 * data_profile_names().size());
  EXPECT_EQ(required.front(), (QosProfileRef{"participant", "p"}));
  for (const std::string& name : data_profile_names()) {
    EXPECT_THAT(required, testing::Contains(QosProfileRef{"data_writer", name}));
    EXPECT_THAT(required, testing::Contains(QosProfileRef{"data_reader", name}));
  }
}

// The profiles checked before a participant exists are exactly robodds_qos.xml's data profiles
// (a profile the file adds but the runtime never asks for would go unchecked) plus the participant.
TEST(QosProfilesXml, RequiredProfilesAreExactlyTheDataProfilesOfRoboddsQosXml) {
  ProfileSet data_in_file;
  for (const auto& [element, name] : profiles_in(read_source_file("deploy/qos/robodds_qos.xml"))) {
    if (element != "participant") {
      data_in_file.emplace(element, name);
    }
  }
  ProfileSet required;
  for (const QosProfileRef& profile : required_profiles(kDefaultParticipantProfile)) {
    if (profile.element != "participant") {
      required.emplace(profile.element, profile.name);
    }
  }
  EXPECT_EQ(required, data_in_file);
}

}  // namespace
}  // namespace robodds
