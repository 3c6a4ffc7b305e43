// make_type_support(): payloads that do not decode are dropped (false) and counted, never thrown.
#include "runtime/dds/type_support.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <vector>

#include "robodds/idl/robodds.h"
#include "runtime/dds/undecodable.hpp"

namespace robodds {
namespace {

using eprosima::fastrtps::rtps::SerializedPayload_t;

SerializedPayload_t payload_of(const std::vector<unsigned char>& bytes) {
  SerializedPayload_t payload(static_cast<std::uint32_t>(bytes.size()));
  std::memcpy(payload.data, bytes.data(), bytes.size());
  payload.length = static_cast<std::uint32_t>(bytes.size());
  return payload;
}

TEST(TypeSupport, DecodesAValidSample) {
  std::unique_ptr<eprosima::fastdds::dds::TopicDataType> type(make_type_support("robodds::idl::VelocityCommand"));
  ASSERT_NE(type, nullptr);
  idl::VelocityCommand sent;
  sent.robot_id(3);
  sent.v(0.25);
  SerializedPayload_t payload(type->m_typeSize);
  ASSERT_TRUE(type->serialize(&sent, &payload));
  idl::VelocityCommand received;
  EXPECT_TRUE(type->deserialize(&payload, &received));
  EXPECT_EQ(received.robot_id(), 3u);
  EXPECT_EQ(received.v(), 0.25);
}

TEST(TypeSupport, ABadEncapsulationHeaderIsDroppedAndCountedNotThrown) {
  const std::string name = "robodds::idl::VelocityCommand";
  std::unique_ptr<eprosima::fastdds::dds::TopicDataType> type(make_type_support(name));
  const std::uint64_t before = undecodable_samples(name);
  std::vector<unsigned char> bytes(76, 0xab);  // first byte not 0: Fast CDR throws BadParamException
  SerializedPayload_t payload = payload_of(bytes);
  idl::VelocityCommand received;
  bool decoded = true;
  EXPECT_NO_THROW(decoded = type->deserialize(&payload, &received));
  EXPECT_FALSE(decoded);
  EXPECT_EQ(undecodable_samples(name), before + 1);
}

TEST(TypeSupport, ABooleanByteOtherThanZeroOrOneIsDroppedAndCounted) {
  const std::string name = "robodds::idl::PoseEstimate";
  std::unique_ptr<eprosima::fastdds::dds::TopicDataType> type(make_type_support(name));
  idl::PoseEstimate sent;
  SerializedPayload_t payload(type->m_typeSize);
  ASSERT_TRUE(type->serialize(&sent, &payload));
  idl::PoseEstimate sent_valid;
  sent_valid.valid(true);
  SerializedPayload_t valid_payload(type->m_typeSize);
  ASSERT_TRUE(type->serialize(&sent_valid, &valid_payload));
  ASSERT_EQ(payload.length, valid_payload.length);
  std::uint32_t valid_at = payload.length;  // the byte of `valid`: the one the two payloads differ in
  for (std::uint32_t i = 0; i < payload.length; ++i) {
    if (payload.data[i] != valid_payload.data[i]) {
      valid_at = i;
    }
  }
  ASSERT_LT(valid_at, payload.length);
  payload.data[valid_at] = 7;
  const std::uint64_t before = undecodable_samples(name);
  idl::PoseEstimate received;
  bool decoded = true;
  EXPECT_NO_THROW(decoded = type->deserialize(&payload, &received));
  EXPECT_FALSE(decoded);
  EXPECT_EQ(undecodable_samples(name), before + 1);
}

TEST(TypeSupport, AShortPayloadIsDroppedAndCounted) {
  const std::string name = "robodds::idl::RobotState";
  std::unique_ptr<eprosima::fastdds::dds::TopicDataType> type(make_type_support(name));
  const std::uint64_t before = undecodable_samples(name);
  SerializedPayload_t payload = payload_of({0x00, 0x01, 0x00, 0x00, 0x01, 0x00});
  idl::RobotState received;
  EXPECT_FALSE(type->deserialize(&payload, &received));
  EXPECT_EQ(undecodable_samples(name), before + 1);
}

}  // namespace
}  // namespace robodds
