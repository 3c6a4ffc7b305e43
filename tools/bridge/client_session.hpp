#pragma once
// One client's subscriptions (subscription id <-> channel id) and its answers to subscribe and
// unsubscribe: which requests are refused and why, one line each. No locking, no sockets.

#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "tools/bridge/protocol.hpp"

namespace robodds::bridge {

class ClientSession {
 public:
  /// Applies `op`; returns one error line per refused request (empty: all done). A subscription
  /// is refused when its channel is not in `advertised`, its id is already in use, or the client
  /// already subscribes that channel; an unsubscribe when the id is unknown. `removed` gets the
  /// ids unsubscribed (their queued messages are to be dropped).
  std::vector<std::string> apply(const ClientOp& op, const std::set<std::uint32_t>& advertised,
                                 std::vector<std::uint32_t>& removed);

  /// Forgets the subscriptions of a channel that is no longer advertised; returns their ids.
  std::vector<std::uint32_t> drop_channel(std::uint32_t channel_id);

  /// The subscription ids of `channel_id` (zero or one).
  const std::vector<std::uint32_t>* subscriptions_of(std::uint32_t channel_id) const;
  std::size_t subscription_count() const { return by_id_.size(); }

 private:
  std::map<std::uint32_t, std::uint32_t> by_id_;                    // subscription id -> channel id
  std::map<std::uint32_t, std::vector<std::uint32_t>> by_channel_;  // channel id -> subscription ids
};

}  // namespace robodds::bridge
