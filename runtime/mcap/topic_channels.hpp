#pragma once
// The MCAP schemas and channels of recorded topics, the one way every recorder of the project
// (`robodds record`, `robodds run --record`) declares them: schema encoding omgidl with the IDL
// text the type needs, message encoding cdr, and the channel metadata a replay needs.

#include <cstdint>
#include <vector>

#include "runtime/mcap/mcap_writer.hpp"
#include "runtime/topics/topic_catalog.hpp"

namespace robodds::mcap {

/// Adds to `writer` one schema per distinct type of `topics` (first use order) and one channel per
/// topic, in the order given; returns the channel ids, parallel to `topics`. Channel metadata:
/// "qos_profile" (the topic's real-time profile) and "key" (its key members, "-" unkeyed).
std::vector<std::uint16_t> add_topic_channels(Writer& writer, const std::vector<const TopicInfo*>& topics);

}  // namespace robodds::mcap
