#include "tests/wan/delay_switch.hpp"

#include <cmath>
#include <stdexcept>

namespace robodds::wan {

namespace {
constexpr std::size_t kEthernetHeaderBytes = 14;

std::uint64_t mac_at(const std::uint8_t* p) {
  std::uint64_t mac = 0;
  for (int i = 0; i < 6; ++i) mac = (mac << 8) | p[i];
  return mac;
}
bool is_group_address(const std::uint8_t* mac) { return (mac[0] & 0x01) != 0; }  // broadcast, multicast
}  // namespace

void DelaySwitchParams::validate() const {
  if (!std::isfinite(delay_s) || delay_s < 0.0) {
    throw std::invalid_argument("delay_s: must be a finite number >= 0 s, got " + std::to_string(delay_s));
  }
  if (!std::isfinite(loss) || loss < 0.0 || loss >= 1.0) {
    throw std::invalid_argument("loss: must be in [0, 1), got " + std::to_string(loss));
  }
  if (max_queued_frames == 0) throw std::invalid_argument("max_queued_frames: must be > 0");
}

DelaySwitch::DelaySwitch(std::size_t ports, const DelaySwitchParams& params)
    : params_(params), queues_(ports), counters_(ports), rng_(params.seed), lose_(params.loss) {
  params_.validate();
  if (ports < 2) throw std::invalid_argument("a switch needs at least 2 ports, got " + std::to_string(ports));
}

void DelaySwitch::receive(std::size_t port, const std::uint8_t* frame, std::size_t size, double now_s) {
  PortCounters& in = counters_.at(port);
  ++in.frames_in;
  in.bytes_in += size;
  if (size < kEthernetHeaderBytes) return;
  const std::uint8_t* destination = frame;
  const std::uint8_t* source = frame + 6;
  if (!is_group_address(source)) port_of_mac_[mac_at(source)] = port;
  const double due_s = now_s + params_.delay_s;
  if (!is_group_address(destination)) {
    const auto known = port_of_mac_.find(mac_at(destination));
    if (known != port_of_mac_.end()) {
      if (known->second != port) enqueue(known->second, frame, size, due_s);
      return;
    }
  }
  for (std::size_t out = 0; out < queues_.size(); ++out) {
    if (out != port) enqueue(out, frame, size, due_s);
  }
}

void DelaySwitch::enqueue(std::size_t port, const std::uint8_t* frame, std::size_t size, double due_s) {
  PortCounters& out = counters_[port];
  if (params_.loss > 0.0 && lose_(rng_)) {
    ++out.lost;
    return;
  }
  if (queues_[port].size() >= params_.max_queued_frames) {
    ++out.overflowed;
    return;
  }
  queues_[port].push_back(Queued{due_s, std::vector<std::uint8_t>(frame, frame + size)});
}

std::vector<DueFrame> DelaySwitch::take_due(double now_s) {
  std::vector<DueFrame> due;
  for (std::size_t port = 0; port < queues_.size(); ++port) {
    auto& queue = queues_[port];
    while (!queue.empty() && queue.front().due_s <= now_s) {
      PortCounters& out = counters_[port];
      ++out.frames_out;
      out.bytes_out += queue.front().frame.size();
      due.push_back(DueFrame{port, std::move(queue.front().frame)});
      queue.pop_front();
    }
  }
  return due;
}

double DelaySwitch::next_due_s() const {
  double next = -1.0;
  for (const auto& queue : queues_) {
    if (!queue.empty() && (next < 0.0 || queue.front().due_s < next)) next = queue.front().due_s;
  }
  return next;
}

double parse_non_negative(const std::string& option, const std::string& text) {
  std::size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || !std::isfinite(value) || value < 0.0) {
    throw std::invalid_argument(option + ": expected a number >= 0, got '" + text + "'");
  }
  return value;
}

}  // namespace robodds::wan
