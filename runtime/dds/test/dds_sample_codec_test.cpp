// The DDS sample codec: serialize() gives the bytes the type support a DDS writer uses writes
// (raw_bus_test checks those are the bytes a raw reader captures on the wire), deserialize() gives
// the sample back, and bytes that do not decode are a ConfigError naming the type and why.
#include "runtime/dds/dds_sample_codec.hpp"

#include <fastdds/rtps/common/SerializedPayload.h>
#include <gtest/gtest.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "robodds/idl/robodds.h"
#include "robodds/idl/robodds_visit.hpp"
#include "runtime/base/error.hpp"
#include "runtime/dds/type_support.hpp"
#include "tests/support/error_of.hpp"

namespace robodds {
namespace {

using eprosima::fastrtps::rtps::SerializedPayload_t;

/// The reference: what the type support of a DDS writer serialises into a payload of the
/// type's maximum size (as raw_bus_test's reference does).
template <class Msg>
std::vector<std::uint8_t> type_support_bytes(const Msg& sample) {
  std::unique_ptr<eprosima::fastdds::dds::TopicDataType> type(make_type_support(idl::type_name<Msg>()));
  SerializedPayload_t payload(type->m_typeSize);
  EXPECT_TRUE(type->serialize(const_cast<Msg*>(&sample), &payload));
  return std::vector<std::uint8_t>(payload.data, payload.data + payload.length);
}

std::string error_of(const std::function<void()>& f) { return test_support::error_of<ConfigError>(f); }

TEST(DdsSampleCodec, SerializesAsTheTypeSupportDoes) {
  const auto codec = make_dds_sample_codec();
  idl::RobotState state;
  state.robot_id(2);
  state.x(1.0 / 3.0);
  state.theta(-0.5);
  EXPECT_EQ(codec->serialize(idl::type_name<idl::RobotState>(), &state), type_support_bytes(state));
  idl::WaypointMission mission;  // a bounded sequence of structs: variable size
  mission.robot_id(1);
  for (int i = 0; i < 3; ++i) {
    idl::Waypoint w;
    w.x(i * 1.5);
    w.y(-i * 0.25);
    mission.waypoints().push_back(w);
  }
  const std::vector<std::uint8_t> bytes = codec->serialize(idl::type_name<idl::WaypointMission>(), &mission);
  EXPECT_EQ(bytes, type_support_bytes(mission));
  ASSERT_GE(bytes.size(), 4u);
  EXPECT_EQ(bytes[0], 0x00) << "XCDR1 encapsulation header";
  EXPECT_EQ(bytes[1], 0x01) << "CDR_LE";
}

// The recorder's path: one serializer per type, one buffer reused for every sample. Whatever the
// buffer held before (here 0xAB bytes, more than any sample), the bytes are the type support's,
// alignment padding zero included.
TEST(DdsSampleCodec, SerializerGivesTheSameBytesIntoAReusedBuffer) {
  const auto codec = make_dds_sample_codec();
  const auto states = codec->serializer(idl::type_name<idl::RobotState>());
  const auto missions = codec->serializer(idl::type_name<idl::WaypointMission>());
  idl::WaypointMission mission;
  mission.robot_id(7);
  std::vector<std::uint8_t> buffer;
  for (int i = 0; i < 4; ++i) {
    idl::Waypoint w;
    w.x(i + 0.5);
    w.y(-i * 2.0);
    mission.waypoints().push_back(w);
    buffer.assign(4096, 0xAB);
    missions->serialize(&mission, buffer);
    EXPECT_EQ(buffer, type_support_bytes(mission)) << i + 1 << " way-points";
    EXPECT_EQ(buffer, codec->serialize(idl::type_name<idl::WaypointMission>(), &mission));
  }
  idl::RobotState state;
  state.robot_id(3);
  state.header().step(42);
  state.v(0.75);
  buffer.assign(4096, 0xAB);
  states->serialize(&state, buffer);
  EXPECT_EQ(buffer, type_support_bytes(state));
  EXPECT_NE(error_of([&] { codec->serializer("robodds::idl::NoSuchType"); }).find("robodds::idl::NoSuchType"),
            std::string::npos);
}

TEST(DdsSampleCodec, DecodesWhatItEncoded) {
  const auto codec = make_dds_sample_codec();
  idl::VelocityCommand sent;
  sent.robot_id(7);
  sent.v(0.125);
  sent.omega(-1.0 / 7.0);
  const std::string name = idl::type_name<idl::VelocityCommand>();
  const std::vector<std::uint8_t> bytes = codec->serialize(name, &sent);
  const std::shared_ptr<void> decoded = codec->deserialize(name, bytes.data(), bytes.size());
  const auto& received = *static_cast<const idl::VelocityCommand*>(decoded.get());
  EXPECT_EQ(received.robot_id(), 7u);
  EXPECT_EQ(received.v(), 0.125);
  EXPECT_EQ(received.omega(), -1.0 / 7.0);
  EXPECT_EQ(codec->serialize(name, decoded.get()), bytes) << "a round trip keeps every byte";
}

TEST(DdsSampleCodec, NamesTheTypeAndWhyBytesDoNotDecode) {
  const auto codec = make_dds_sample_codec();
  const std::string name = idl::type_name<idl::RobotState>();
  idl::RobotState state;
  const std::vector<std::uint8_t> bytes = codec->serialize(name, &state);
  EXPECT_NE(error_of([&] { codec->serialize("robodds::idl::NoSuchType", &state); }).find("robodds::idl::NoSuchType"),
            std::string::npos);
  EXPECT_NE(error_of([&] { codec->deserialize("robodds::idl::NoSuchType", bytes.data(), bytes.size()); })
                .find("not one of the IDL topic types"),
            std::string::npos);
  std::vector<std::uint8_t> bad = bytes;
  bad[0] = 0xab;
  const std::string encapsulation = error_of([&] { codec->deserialize(name, bad.data(), bad.size()); });
  EXPECT_NE(encapsulation.find(name), std::string::npos) << encapsulation;
  EXPECT_NE(encapsulation.find("encapsulation"), std::string::npos) << encapsulation;
  const std::string truncated = error_of([&] { codec->deserialize(name, bytes.data(), bytes.size() / 2); });
  EXPECT_NE(truncated.find("truncated"), std::string::npos) << truncated;
  EXPECT_NE(error_of([&] { codec->deserialize(name, bytes.data(), 2); }).find("encapsulation header"), std::string::npos);
}

TEST(DdsSampleCodec, IsInstalledOnceWhereDdsIsSetUp) {
  set_sample_codec(nullptr);
  EXPECT_NE(error_of([] { sample_codec(); }).find("no sample codec installed"), std::string::npos);
  install_dds_sample_codec();  // what make_dds_bus() and make_raw_bus() call
  idl::RobotState state;
  state.robot_id(4);
  EXPECT_EQ(sample_codec().serialize(idl::type_name<idl::RobotState>(), &state), type_support_bytes(state));
}

}  // namespace
}  // namespace robodds
