#pragma once
// Is a recording complete enough to drive a lockstep run? Every sample announces its producer's
// next step for its instance (SampleHeader::next_step); in lockstep a consumer waits for that
// sample, so a recording that lost one would stall the re-run until its input timeout. Checked
// before the run starts, on the headers alone (std only).

#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace robodds::replay_source {

/// One recorded sample's place in its stream.
struct ChainLink {
  std::string topic;   // e.g. "sensor/position"
  std::string stream;  // topic and instance, e.g. "sensor/position (robot_id=1)"
  std::uint64_t step = 0;
  std::uint64_t next_step = 0;  // kNeverAgain (2^64 - 1): the last of its instance
  std::uint64_t key = 0;        // its instance key (idl::instance_key: robot << 32 | peer for a pair)
};

/// The first problem, one line, or empty when every stream is whole up to `last_step` (the re-run's
/// last step): no two samples of one step in a stream; each sample's announced step is the next
/// sample's step; a stream whose last sample announces a step the recording did not reach (past
/// its last recorded step) but the re-run does (<= last_step) is cut short. A stream whose last
/// announced step lies inside the recording and never came has ended (its producer moved the robot
/// to another key, e.g. a new target): not a problem, as in the original run.
std::string chain_problem(const std::vector<ChainLink>& links, std::uint64_t last_step);

/// "TOPIC: its first recorded sample is of step N" for each topic none of whose samples is of
/// step 0: a recorder that joined after the run started (a warning: a topic may also start late
/// on purpose).
std::vector<std::string> late_topics(const std::vector<ChainLink>& links);

/// The instances of each topic of `topics` in `links`: topic -> keys ascending, once each (what a
/// replay source declares with ComponentContext::publishes_instances(): a topic keyed by a pair of
/// robots, whose instances only its producer knows). A topic without a link maps to nothing.
std::map<std::string, std::vector<std::uint64_t>> instances_of(const std::vector<ChainLink>& links,
                                                              const std::set<std::string>& topics);

/// The first link of `topics` (keyed robot_id, peer_id: key = robot << 32 | peer) whose robot is
/// not among `served` (the replay source's robots) or whose peer is not among `robots` (the
/// scenario's): "STREAM: robot N is not ...", one line; empty when every pair is of these robots.
/// Such a pair would be declared and published for a robot the run does not have.
std::string foreign_pair(const std::vector<ChainLink>& links, const std::set<std::string>& topics,
                         const std::vector<std::uint32_t>& served, const std::vector<std::uint32_t>& robots);

}  // namespace robodds::replay_source
