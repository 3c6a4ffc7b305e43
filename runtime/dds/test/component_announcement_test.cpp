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

}  // namespace
}  // namespace robodds
