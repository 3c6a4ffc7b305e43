// The participant USER_DATA announcing a host's components (runtime/dds/component_announcement.hpp).
#include "runtime/dds/component_announcement.hpp"

#include <gtest/gtest.h>

namespace robodds {
namespace {

TEST(ComponentAnnouncement, RoundTrips) {
  const std::vector<std::string> components = {"plant", "position_sensor"};
  EXPECT_EQ(announced_components(component_announcement(components)), components);
  EXPECT_EQ(announced_components(component_announcement({})), std::vector<std::string>{});
}

TEST(ComponentAnnouncement, OtherUserDataIsNoAnnouncement) {
  EXPECT_FALSE(announced_components({}));
  const std::string other = "robodds-component:plant";  // not our prefix
  EXPECT_FALSE(announced_components(std::vector<std::uint8_t>(other.begin(), other.end())));
}

std::vector<std::uint8_t> bytes(const std::string& text) { return std::vector<std::uint8_t>(text.begin(), text.end()); }

TEST(ComponentAnnouncement, CarriesTheRunAndTheDigestOfWhatTheHostLoaded) {
  const RunDigest digest = {{"scenario", "/x/s.yaml", "00ff"}, {"qos:robodds_qos.xml", "/q/robodds_qos.xml", "abcd"}};
  const std::optional<Announcement> a = parse_announcement(component_announcement({"plant"}, 42, digest));
  ASSERT_TRUE(a);
  EXPECT_EQ(a->components, std::vector<std::string>{"plant"});
  EXPECT_EQ(a->run_id, std::optional<std::uint64_t>(42));
  EXPECT_EQ(a->digest, (std::map<std::string, std::string>{{"scenario", "00ff"}, {"qos:robodds_qos.xml", "abcd"}}));
  // The components alone, as before, for a participant without a run (a tool, a component executable).
  EXPECT_EQ(announced_components(component_announcement({"plant"}, 42, digest)), std::vector<std::string>{"plant"});
  EXPECT_FALSE(parse_announcement(component_announcement({"plant"}))->run_id);
}

// What another participant sends is untrusted: anything not exactly our shape, or too long, is no
// announcement (its writers are no producer), and nothing in it can throw or grow without bound.
TEST(ComponentAnnouncement, MalformedOrOversizedUserDataIsNoAnnouncement) {
  const char* bad[] = {
      "robodds-components:a\nrobodds-run:x",                          // run id not a number
      "robodds-components:a\nrobodds-run:-1",                         // nor negative
      "robodds-components:a\nrobodds-run:99999999999999999999999",    // nor beyond 64 bits
      "robodds-components:a\nrobodds-digest:scenario=00",             // digest without a run
      "robodds-components:a\nrobodds-run:1\nrobodds-digest:scenario", // no '='
      "robodds-components:a\nrobodds-run:1\nrobodds-digest:=00",      // no label
      "robodds-components:a\nrobodds-run:1\nrobodds-digest:scenario=XYZ",  // not hex
      "robodds-components:a\nrobodds-run:1\nrobodds-digest:a b=00",   // a space in a label
      "robodds-components:a\nrobodds-run:1\nrobodds-digest:a=00;a=01",  // a label twice
      "robodds-components:a\nrobodds-run:1\nrobodds-digest:a=00\nmore",  // a fourth line
  };
  for (const char* text : bad) {
    EXPECT_FALSE(parse_announcement(bytes(text))) << text;
  }
  std::string zero = "robodds-components:a";
  zero += '\0';
  EXPECT_FALSE(parse_announcement(bytes(zero)));
  EXPECT_FALSE(parse_announcement(bytes("robodds-components:" + std::string(kMaxAnnouncementBytes, 'a'))));
  std::string many = "robodds-components:a\nrobodds-run:1\nrobodds-digest:";
  for (std::size_t i = 0; i <= kMaxDigestEntries; ++i) {
    many += (i == 0 ? "" : ";") + std::string("l") + std::to_string(i) + "=00";
  }
  EXPECT_FALSE(parse_announcement(bytes(many)));
  EXPECT_TRUE(parse_announcement(bytes("robodds-components:a\nrobodds-run:1\nrobodds-digest:l.x:y_z-1=0a")));
}

}  // namespace
}  // namespace robodds
