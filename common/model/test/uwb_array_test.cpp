// The UWB arrays shared by the sensor and the relative-pose estimator: the labelling convention,
// the validation of node lists, and the true ranges between two arrays.
#include "common/model/uwb_array.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "common/angle.hpp"

namespace robodds::model {
namespace {

std::string message_of(const UwbArray& array) {
  try {
    check_array("nodes_m", array);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "ok";
}

TEST(SquareArray, LabelsGoCounterClockwiseFromFrontLeft) {
  const UwbArray a = square_array(0.5);
  ASSERT_EQ(a.nodes_m.size(), 4u);
  EXPECT_EQ(a.nodes_m[0], Eigen::Vector2d(0.25, 0.25));
  EXPECT_EQ(a.nodes_m[1], Eigen::Vector2d(-0.25, 0.25));
  EXPECT_EQ(a.nodes_m[2], Eigen::Vector2d(-0.25, -0.25));
  EXPECT_EQ(a.nodes_m[3], Eigen::Vector2d(0.25, -0.25));
  EXPECT_THROW(square_array(0.0), std::invalid_argument);
  EXPECT_EQ(message_of(a), "ok");
}

TEST(CheckArray, FewerThanThreeNodesOrCoincidentNodesNameTheKey) {
  EXPECT_EQ(message_of(UwbArray{{{0.0, 0.0}, {1.0, 0.0}}}), "nodes_m: needs at least 3 nodes (a relative heading needs them) (got 2 nodes)");
  EXPECT_EQ(message_of(UwbArray{{{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}}}), "ok");
  EXPECT_EQ(message_of(UwbArray{{{0.0, 0.0}, {1.0, 0.0}, {0.0005, 0.0}}}),
            "nodes_m: nodes 0 and 2 coincide (closer than 0.001 m) (got 5e-04 m apart)");
  EXPECT_EQ(message_of(UwbArray{{{0.0, 0.0}, {0.0011, 0.0}, {0.0, 1.0}}}), "ok") << "just above the spacing";
  EXPECT_EQ(message_of(UwbArray{{{0.0, 0.0}, {1.0, 0.0}, {std::numeric_limits<double>::quiet_NaN(), 1.0}}}),
            "nodes_m: node 2 must have finite coordinates (got [nan, 1])");
}

TEST(ArrayRanges, AreTheDistancesOfTheNodesInTheWorld) {
  // Robot a at the origin facing +y: its front-left node (0.25, 0.25) sits at (-0.25, 0.25).
  const UwbArray a = square_array(0.5);
  EXPECT_TRUE(node_in_world(Pose2{0.0, 0.0, kPi / 2.0}, a.nodes_m[0]).isApprox(Eigen::Vector2d(-0.25, 0.25)));
  // Robot b at (3, 0) facing -x: its node 2 (-0.25, -0.25) sits at (3.25, 0.25).
  const Pose2 pose_a{0.0, 0.0, kPi / 2.0};
  const Pose2 pose_b{3.0, 0.0, kPi};
  const Eigen::MatrixXd r = array_ranges(a, pose_a, a, pose_b);
  ASSERT_EQ(r.rows(), 4);
  ASSERT_EQ(r.cols(), 4);
  EXPECT_NEAR(r(0, 2), 3.5, 1e-12) << "(-0.25, 0.25) to (3.25, 0.25)";
  // Symmetric: the ranges seen from b are the transpose.
  EXPECT_TRUE(array_ranges(a, pose_b, a, pose_a).isApprox(r.transpose(), 1e-15));
}

}  // namespace
}  // namespace robodds::model
