// Which UWB links a wall blocks (experiment 1-b's board): segment crossing, touching ends, and the
// K x L mask for two robots on either side of a wall or beside it.
#include "components/uwb_sensor/uwb_walls.hpp"

#include <gtest/gtest.h>

namespace robodds::uwb_sensor {
namespace {

using V = Eigen::Vector2d;

TEST(SegmentsCross, ProperCrossingsTouchingAndMisses) {
  EXPECT_TRUE(segments_cross(V(-1, 0), V(1, 0), V(0, -1), V(0, 1))) << "an X";
  EXPECT_FALSE(segments_cross(V(-1, 0), V(1, 0), V(2, -1), V(2, 1))) << "the wall is beyond the link's end";
  EXPECT_FALSE(segments_cross(V(-1, 0), V(1, 0), V(-1, 1), V(1, 1))) << "parallel";
  EXPECT_TRUE(segments_cross(V(-1, 0), V(1, 0), V(1, -1), V(1, 1))) << "the link ends on the wall";
  EXPECT_TRUE(segments_cross(V(1, 0), V(3, 0), V(1, -1), V(1, 1))) << "the link starts on the wall";
  EXPECT_TRUE(segments_cross(V(-1, 0), V(1, 0), V(0, 0), V(0, 3))) << "the wall's end on the link: grazing blocks";
  EXPECT_TRUE(segments_cross(V(-1, 0), V(1, 0), V(0, 3), V(0, 0))) << "the wall's other end on the link";
  EXPECT_TRUE(segments_cross(V(0, 0), V(2, 0), V(1, 0), V(3, 0))) << "collinear overlap";
  EXPECT_FALSE(segments_cross(V(0, 0), V(1, 0), V(2, 0), V(3, 0))) << "collinear, apart";
  EXPECT_FALSE(segments_cross(V(0, 0), V(1, 1), V(0, 1), V(0.4, 0.6))) << "the wall stops short of the link";
}

TEST(LinksThroughWalls, AWallBetweenTheRobotsBlocksEveryLinkAndNoneBeside) {
  const model::UwbArray array = model::square_array(0.5);
  const model::Pose2 a{0.0, 0.0, 0.0};
  const model::Pose2 b{4.0, 0.0, 1.0};
  EXPECT_EQ(links_through_walls(array, a, array, b, {}).size(), 0) << "no walls: an empty mask";
  const BlockedLinks between = links_through_walls(array, a, array, b, {Wall{V(2, -1), V(2, 1)}});
  ASSERT_EQ(between.rows(), 4);
  ASSERT_EQ(between.cols(), 4);
  EXPECT_TRUE(between.all());
  EXPECT_FALSE(links_through_walls(array, a, array, b, {Wall{V(2, 1), V(2, 3)}}).any()) << "a wall beside the line of sight";
}

// A short wall at the edge of the line of sight blocks the links on its side only.
TEST(LinksThroughWalls, AShortWallBlocksTheLinksOnItsSide) {
  const model::UwbArray array = model::square_array(0.5);  // nodes at y = +-0.25 on both robots
  const BlockedLinks half =
      links_through_walls(array, model::Pose2{0, 0, 0}, array, model::Pose2{4, 0, 0}, {Wall{V(2, 0.1), V(2, 1)}});
  for (Eigen::Index k = 0; k < 4; ++k) {
    for (Eigen::Index l = 0; l < 4; ++l) {
      const bool k_left = array.nodes_m[static_cast<std::size_t>(k)].y() > 0;
      const bool l_left = array.nodes_m[static_cast<std::size_t>(l)].y() > 0;
      // Left-to-left links (y = 0.25 all the way) are blocked; right-to-right ones pass under the
      // wall; the diagonals cross x = 2 at y = 0, below the wall's end at 0.1.
      EXPECT_EQ(half(k, l), k_left && l_left) << "link " << k << "-" << l;
    }
  }
}

}  // namespace
}  // namespace robodds::uwb_sensor
