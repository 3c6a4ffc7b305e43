// ReaderKeyFilter: a sample passes when a subscriber takes its key or takes every key; otherwise
// every subscriber is told (refused) and it is dropped; a payload that does not decode is dropped.
#include "runtime/dds/key_filter.hpp"

#include <fastdds/dds/core/LoanableSequence.hpp>
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "robodds/idl/robodds.h"
#include "runtime/dds/type_support.hpp"
#include "runtime/dds/undecodable.hpp"

namespace robodds {
namespace {

using eprosima::fastrtps::rtps::SerializedPayload_t;
namespace dds = eprosima::fastdds::dds;

const char* const kType = "robodds::idl::VelocityCommand";

SerializedPayload_t command_of(const dds::TypeSupport& type, std::uint32_t robot, std::uint64_t step = 0,
                               std::uint64_t next_step = 1) {
  idl::VelocityCommand sample;
  sample.robot_id(robot);
  sample.header().step(step);
  sample.header().next_step(next_step);
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
  KeyFilterFactory factory("robodds.keys.test", nullptr);
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

TEST(ReaderKeyFilter, WithReadStepsOnlyTheSamplesOfThoseStepsPassAfterTheKeys) {
  dds::TypeSupport type(make_type_support(kType));
  ReaderKeyFilter filter(type, kType);
  Subscriber a;
  filter.add(a.filter());
  filter.read_only(StepNeeds::of_component(10, 0, 0));
  EXPECT_TRUE(passes(filter, command_of(type, 1, 20, 21)));
  EXPECT_FALSE(passes(filter, command_of(type, 1, 21, 22)));
  EXPECT_TRUE(passes(filter, command_of(type, 2, 25, 31))) << "the newest at step 30";
  EXPECT_FALSE(passes(filter, command_of(type, 7, 20, 21))) << "a key no subscriber takes, whatever its step";
  EXPECT_EQ(a.refused, (std::vector<std::uint64_t>{7}));
  EXPECT_EQ(filter.left_out(), 1u);
  EXPECT_EQ(filter.dropped(), 1u);
}

TEST(ReaderKeyFilter, ReadStepsAloneFilterEveryKeysSamples) {
  dds::TypeSupport type(make_type_support(kType));
  ReaderKeyFilter filter(type, kType);
  filter.add_unfiltered();
  filter.read_only(StepNeeds::of_component(5, 0, 1));  // steps 4, 9, 14, ...
  EXPECT_TRUE(passes(filter, command_of(type, 20000, 9, 10)));
  EXPECT_FALSE(passes(filter, command_of(type, 20000, 10, 11)));
  filter.read_only(StepNeeds{});
  EXPECT_TRUE(passes(filter, command_of(type, 20000, 10, 11))) << "every step again";
}

TEST(KeyFilterFactory, MakesAWriterSideStepFilterForARemoteReadersExpression) {
  dds::TypeSupport type(make_type_support(kType));
  KeyFilterFactory factory("robodds.keys.test", [type](const std::string& name) {
    return name == kType ? type : dds::TypeSupport();
  });
  dds::LoanableSequence<const char*> none;
  using eprosima::fastrtps::types::ReturnCode_t;
  dds::IContentFilter* made = nullptr;
  ASSERT_EQ(factory.create_content_filter(KeyFilterFactory::kStepClass, kType, nullptr,
                                          "steps 10:0|plant/cmd|lockstep|01.0f.aa", none, made),
            ReturnCode_t::RETCODE_OK);
  ASSERT_NE(made, nullptr);
  const auto& writer_side = *static_cast<ReaderKeyFilter*>(made);
  EXPECT_TRUE(passes(writer_side, command_of(type, 20000, 30, 31))) << "keys are the reader's business";
  EXPECT_FALSE(passes(writer_side, command_of(type, 1, 31, 32)));
  SerializedPayload_t empty(0);  // e.g. an instance's end, key only
  EXPECT_TRUE(passes(writer_side, empty)) << "what a writer cannot decode, the reader judges";
  EXPECT_EQ(factory.delete_content_filter(KeyFilterFactory::kStepClass, made), ReturnCode_t::RETCODE_OK);

  for (const char* bad : {"steps 10:10|x", "keys|plant/cmd", "", "steps 0:0"}) {
    dds::IContentFilter* refused = nullptr;
    EXPECT_NE(factory.create_content_filter(KeyFilterFactory::kStepClass, kType, nullptr, bad, none, refused),
              ReturnCode_t::RETCODE_OK)
        << bad;
    EXPECT_EQ(refused, nullptr) << bad;
  }
  dds::IContentFilter* unknown_type = nullptr;
  EXPECT_NE(factory.create_content_filter(KeyFilterFactory::kStepClass, "robodds::idl::NoSuchType", nullptr, "steps 10:0|x",
                                          none, unknown_type),
            ReturnCode_t::RETCODE_OK);
}

TEST(ReaderKeyFilter, AWriterSideFilterReadsTheStepsOfTheSampleThisThreadIsWritingInsteadOfDecoding) {
  dds::TypeSupport type(make_type_support(kType));
  ReaderKeyFilter writer_side(type, kType, ReaderKeyFilter::Side::kWriter);
  writer_side.read_only(StepNeeds::of_component(10, 0, 0));
  const SerializedPayload_t undecodable(0);  // proves the verdict came from the sample, not a decode
  idl::VelocityCommand sample;
  sample.header().step(30);
  sample.header().next_step(31);
  {
    const SampleBeingWritten writing(&sample, sample_steps_function(kType));
    EXPECT_EQ(SampleBeingWritten::of_type(sample_steps_function(kType)), &sample);
    EXPECT_TRUE(passes(writer_side, undecodable));
    sample.header().step(31);
    sample.header().next_step(32);
    EXPECT_FALSE(passes(writer_side, undecodable)) << "step 31 is read at no step";
    EXPECT_EQ(writer_side.left_out(), 1u);

    ReaderKeyFilter reader_side(type, kType);  // a reader judges the payload it received, never the mark
    reader_side.read_only(StepNeeds::of_component(10, 0, 0));
    EXPECT_FALSE(passes(reader_side, undecodable));
    EXPECT_EQ(reader_side.dropped(), 1u);
  }
  EXPECT_EQ(SampleBeingWritten::of_type(sample_steps_function(kType)), nullptr) << "the mark ends with the write";
  {
    idl::VelocityCommand inner;
    const SampleBeingWritten outer_mark(&sample, sample_steps_function(kType));
    {
      const SampleBeingWritten inner_mark(&inner, sample_steps_function(kType));
      EXPECT_EQ(SampleBeingWritten::of_type(sample_steps_function(kType)), &inner);
    }
    EXPECT_EQ(SampleBeingWritten::of_type(sample_steps_function(kType)), &sample) << "the outer mark is back";
  }
  EXPECT_TRUE(passes(writer_side, undecodable)) << "no mark: decoded, and what does not decode passes";
  {
    const SampleBeingWritten writing(&sample, sample_steps_function("robodds::idl::RobotState"));
    EXPECT_EQ(SampleBeingWritten::of_type(sample_steps_function(kType)), nullptr) << "a sample of another type is not this filter's";
    EXPECT_FALSE(passes(writer_side, command_of(type, 1, 31, 32))) << "decoded";
  }
}

}  // namespace
}  // namespace robodds
