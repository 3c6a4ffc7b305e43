#include "tools/bridge/client_queue.hpp"

#include <algorithm>

namespace robodds::bridge {

ClientQueue::ClientQueue(std::size_t capacity) : capacity_(std::max<std::size_t>(capacity, 1)) {}

bool ClientQueue::push(Queued message) {
  bool kept_all = true;
  while (queue_.size() >= capacity_) {
    queue_.pop_front();
    ++dropped_;
    kept_all = false;
  }
  queue_.push_back(std::move(message));
  return kept_all;
}

std::vector<Queued> ClientQueue::take(std::size_t max) {
  const std::size_t n = std::min(max, queue_.size());
  std::vector<Queued> out(std::make_move_iterator(queue_.begin()), std::make_move_iterator(queue_.begin() + static_cast<std::ptrdiff_t>(n)));
  queue_.erase(queue_.begin(), queue_.begin() + static_cast<std::ptrdiff_t>(n));
  return out;
}

void ClientQueue::remove_subscription(std::uint32_t subscription_id) {
  queue_.erase(std::remove_if(queue_.begin(), queue_.end(),
                              [&](const Queued& q) { return q.subscription_id == subscription_id; }),
               queue_.end());
}

}  // namespace robodds::bridge
