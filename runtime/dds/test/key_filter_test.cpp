// ReaderKeyFilter: a sample passes when a subscriber takes its key or takes every key; otherwise
// every subscriber is told (refused) and it is dropped; a payload that does not decode is dropped.
#include "runtime/dds/key_filter.hpp"

#include <fastdds/dds/core/LoanableSequence.hpp>
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "robodds/idl/robodds.h"
#include "runtime/dds/type_support.hpp"
#include "runtime/dds/undecodable.hpp"

namespace robodds {
namespace {

using eprosima::fastrtps::rtps::SerializedPayload_t;
namespace dds = eprosima::fastdds::dds;

const char* const kType = "robodds::idl::VelocityCommand";

SerializedPayload_t command_of(const dds::TypeSupport& type, std::uint32_t robot) {
  idl::VelocityCommand sample;
  sample.robot_id(robot);
  SerializedPayload_t payload(type->m_typeSize);
  EXPECT_TRUE(type->serialize(&sample, &payload));
  return payload;
}

/// A subscriber that takes robots 1 and 2 and records what the filter refused.
struct Subscriber {
  std::vector<std::uint64_t> refused;
  KeyFilter filter() {
    return KeyFilter{[](std::uint64_t key) { return key == 1 || key == 2; },
                     [this](std::uint64_t key, std::uint64_t) { refused.push_back(key); }};
  }
};

bool passes(const ReaderKeyFilter& filter, const SerializedPayload_t& payload) {
  return filter.evaluate(payload, dds::IContentFilter::FilterSampleInfo{}, eprosima::fastrtps::rtps::GUID_t{});
}

TEST(ReaderKeyFilter, KeysNoSubscriberTakesAreDroppedAndEverySubscriberIsTold) {
  dds::TypeSupport type(make_type_support(kType));
  ReaderKeyFilter filter(type, kType);
  Subscriber a, b;
  filter.add(a.filter());
  filter.add(b.filter());
  EXPECT_TRUE(filter.filters());
  EXPECT_TRUE(passes(filter, command_of(type, 1)));
  EXPECT_TRUE(passes(filter, command_of(type, 2)));
  EXPECT_FALSE(passes(filter, command_of(type, 20000)));
  EXPECT_FALSE(passes(filter, command_of(type, 3)));
  EXPECT_EQ(a.refused, (std::vector<std::uint64_t>{20000, 3}));
  EXPECT_EQ(b.refused, a.refused);
  EXPECT_EQ(filter.dropped(), 2u);
}

TEST(ReaderKeyFilter, ASubscriberWithoutARuleTakesEveryKey) {
  dds::TypeSupport type(make_type_support(kType));
  ReaderKeyFilter filter(type, kType);
  Subscriber a;
  filter.add(a.filter());
  filter.add_unfiltered();
  EXPECT_FALSE(filter.filters());
  EXPECT_TRUE(passes(filter, command_of(type, 20000)));
  EXPECT_TRUE(a.refused.empty());
}

TEST(ReaderKeyFilter, WithoutSubscribersItFiltersNothing) {
  dds::TypeSupport type(make_type_support(kType));
  ReaderKeyFilter filter(type, kType);
  EXPECT_FALSE(filter.filters());
  EXPECT_TRUE(passes(filter, command_of(type, 20000)));
}

TEST(ReaderKeyFilter, APayloadThatDoesNotDecodeIsDroppedAndCountedAsUndecodable) {
  dds::TypeSupport type(make_type_support(kType));
  ReaderKeyFilter filter(type, kType);
  Subscriber a;
  filter.add(a.filter());
  SerializedPayload_t payload = command_of(type, 1);
  payload.data[0] = 0xab;  // not an encapsulation header
  const std::uint64_t before = undecodable_samples(kType);
  EXPECT_FALSE(passes(filter, payload));
  EXPECT_EQ(undecodable_samples(kType), before + 1);
  EXPECT_TRUE(a.refused.empty());  // not a key: counted as undecodable only
  SerializedPayload_t empty(0);      // e.g. a dispose that carries only a key hash
  EXPECT_FALSE(passes(filter, empty));
}

TEST(KeyFilterFactory, HandsOutTheFilterOfAnExpressionOfItsOwnClassOnly) {
  dds::TypeSupport type(make_type_support(kType));
  ReaderKeyFilter filter(type, kType);
  KeyFilterFactory factory("robodds.keys.test");
  factory.add("plant/cmd|keys|command", &filter);
  dds::LoanableSequence<const char*> none;
  dds::IContentFilter* made = nullptr;
  using eprosima::fastrtps::types::ReturnCode_t;
  EXPECT_EQ(factory.create_content_filter("robodds.keys.test", kType, nullptr, "plant/cmd|keys|command", none, made),
            ReturnCode_t::RETCODE_OK);
  EXPECT_EQ(made, &filter);
  dds::IContentFilter* other = nullptr;
  EXPECT_NE(factory.create_content_filter("robodds.keys.other", kType, nullptr, "plant/cmd|keys|command", none, other),
            ReturnCode_t::RETCODE_OK);
  EXPECT_NE(factory.create_content_filter("robodds.keys.test", kType, nullptr, "sensor/position|keys|sensor", none, other),
            ReturnCode_t::RETCODE_OK);
  EXPECT_EQ(other, nullptr);
  EXPECT_EQ(factory.delete_content_filter("robodds.keys.test", made), ReturnCode_t::RETCODE_OK);
}

}  // namespace
}  // namespace robodds
