// FastDdsBus::undecodable_samples(): the type support's per-type counts, credited to the topics
// this bus reads. A real participant on domain 83 (the counters helper's test domain); no reader
// is started, so nothing goes on the wire.
#include "runtime/dds/dds_bus.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <memory>

#include "robodds/idl/robodds.h"
#include "runtime/dds/type_support.hpp"

namespace robodds {
namespace {

TEST(FastDdsBus, CreditsItsInputTopicsWithTheUndecodableSamplesOfTheirType) {
  DdsOptions options;
  options.domain_id = 83;
  options.qos_files = {std::string(ROBODDS_SOURCE_DIR) + "/deploy/qos/robodds_qos.xml"};
  auto bus = make_dds_bus(options);
  const std::string type_name = "robodds::idl::VelocityCommand";
  bus->reader("plant/cmd", type_name, "command", [](const void*, const SampleMeta&) {}, nullptr);
  EXPECT_EQ(bus->undecodable_samples().count("plant/cmd"), 0u) << "nothing dropped yet";

  // A payload with a bad encapsulation header, as the Fast DDS reader would hand it over.
  std::unique_ptr<eprosima::fastdds::dds::TopicDataType> type(make_type_support(type_name));
  eprosima::fastrtps::rtps::SerializedPayload_t payload(8);
  const unsigned char bytes[8] = {0x7f, 0x7f, 0, 0, 1, 2, 3, 4};
  std::memcpy(payload.data, bytes, sizeof bytes);
  payload.length = sizeof bytes;
  idl::VelocityCommand sample;
  EXPECT_FALSE(type->deserialize(&payload, &sample));
  EXPECT_FALSE(type->deserialize(&payload, &sample));

  const auto counts = bus->undecodable_samples();
  ASSERT_EQ(counts.count("plant/cmd"), 1u);
  EXPECT_EQ(counts.at("plant/cmd"), 2u);
  EXPECT_EQ(counts.size(), 1u) << "only the topics this bus reads";
}

}  // namespace
}  // namespace robodds
