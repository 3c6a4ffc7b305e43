#include "tools/bridge/client_session.hpp"

#include <algorithm>

namespace robodds::bridge {

std::vector<std::string> ClientSession::apply(const ClientOp& op, const std::set<std::uint32_t>& advertised,
                                              std::vector<std::uint32_t>& removed) {
  std::vector<std::string> errors;
  switch (op.kind) {
    case ClientOp::Kind::kSubscribe:
      for (const auto& [id, channel] : op.subscribe) {
        if (advertised.count(channel) == 0) {
          errors.push_back("subscribe: channel " + std::to_string(channel) + " is not advertised (subscription " +
                           std::to_string(id) + " ignored)");
        } else if (by_id_.count(id) != 0) {
          errors.push_back("subscribe: subscription id " + std::to_string(id) + " is already in use (channel " +
                           std::to_string(by_id_.at(id)) + ")");
        } else if (by_channel_.count(channel) != 0) {
          errors.push_back("subscribe: channel " + std::to_string(channel) + " is already subscribed as subscription " +
                           std::to_string(by_channel_.at(channel).front()));
        } else {
          by_id_[id] = channel;
          by_channel_[channel].push_back(id);
        }
      }
      break;
    case ClientOp::Kind::kUnsubscribe:
      for (const std::uint32_t id : op.unsubscribe) {
        const auto it = by_id_.find(id);
        if (it == by_id_.end()) {
          errors.push_back("unsubscribe: no subscription " + std::to_string(id));
          continue;
        }
        auto& ids = by_channel_[it->second];
        ids.erase(std::remove(ids.begin(), ids.end(), id), ids.end());
        if (ids.empty()) {
          by_channel_.erase(it->second);
        }
        by_id_.erase(it);
        removed.push_back(id);
      }
      break;
    case ClientOp::Kind::kUnsupported:
      errors.push_back("operation '" + op.op + "' is not supported by robodds bridge (it streams topics: subscribe, unsubscribe)");
      break;
  }
  return errors;
}

std::vector<std::uint32_t> ClientSession::drop_channel(std::uint32_t channel_id) {
  const auto it = by_channel_.find(channel_id);
  if (it == by_channel_.end()) {
    return {};
  }
  std::vector<std::uint32_t> ids = it->second;
  for (const std::uint32_t id : ids) {
    by_id_.erase(id);
  }
  by_channel_.erase(it);
  return ids;
}

const std::vector<std::uint32_t>* ClientSession::subscriptions_of(std::uint32_t channel_id) const {
  const auto it = by_channel_.find(channel_id);
  return it == by_channel_.end() ? nullptr : &it->second;
}

}  // namespace robodds::bridge
