#pragma once
// The forwarding logic of robodds-wan-switch (tests/wan): an Ethernet learning switch whose every
// port-to-port delivery takes a fixed one-way delay and may be lost. It holds no sockets or
// devices (the program feeds it frames and writes out what is due), so its behaviour is tested
// on its own (tests/wan/test/delay_switch_test.cpp).
//
// Why not the kernel: this VM's kernel has no netem qdisc, so a link with a WAN's latency is made
// in user space: every host's eth0 is a TAP device whose other end is this switch.

#include <cstddef>
#include <cstdint>
#include <deque>
#include <map>
#include <random>
#include <string>
#include <vector>

namespace robodds::wan {

struct DelaySwitchParams {
  double delay_s = 0.0;      // one-way delay of every frame from port to port, s, >= 0
  double loss = 0.0;         // probability that a frame is lost on its way to one port, [0, 1)
  std::uint64_t seed = 1;    // seeds the loss draws: the same frames lose the same deliveries
  std::size_t max_queued_frames = 200000;  // per output port; beyond it frames are dropped (counted)

  // Throws std::invalid_argument naming the field and the reason.
  void validate() const;
};

struct PortCounters {
  std::uint64_t frames_in = 0;     // frames received from this port's host
  std::uint64_t bytes_in = 0;
  std::uint64_t frames_out = 0;    // frames delivered to this port's host
  std::uint64_t bytes_out = 0;
  std::uint64_t lost = 0;          // deliveries to this port dropped by the loss draw
  std::uint64_t overflowed = 0;    // deliveries to this port dropped because its queue was full
};

struct DueFrame {
  std::size_t port;
  std::vector<std::uint8_t> frame;
};

class DelaySwitch {
 public:
  DelaySwitch(std::size_t ports, const DelaySwitchParams& params);

  // A frame that arrived from `port` at time `now_s` (s, any monotonic origin). Learns the source
  // MAC; queues a copy for the destination's port (known unicast) or every other port (broadcast,
  // multicast, unknown), each due at now_s + delay_s unless lost. Frames shorter than an Ethernet
  // header are counted in and dropped.
  void receive(std::size_t port, const std::uint8_t* frame, std::size_t size, double now_s);

  // Every frame due at or before now_s, in the order they were queued per port (ports in turn).
  std::vector<DueFrame> take_due(double now_s);

  // Time (s) at which the next queued frame is due; a negative value when nothing is queued.
  double next_due_s() const;

  const PortCounters& counters(std::size_t port) const { return counters_.at(port); }
  std::size_t ports() const { return queues_.size(); }

 private:
  struct Queued {
    double due_s;
    std::vector<std::uint8_t> frame;
  };
  void enqueue(std::size_t port, const std::uint8_t* frame, std::size_t size, double due_s);

  DelaySwitchParams params_;
  std::vector<std::deque<Queued>> queues_;  // FIFO per output port: one delay keeps the order
  std::vector<PortCounters> counters_;
  std::map<std::uint64_t, std::size_t> port_of_mac_;  // bounded by the hosts' MACs (a test's few)
  std::mt19937_64 rng_;
  std::bernoulli_distribution lose_;
};

// "12.5" -> 12.5 with the option's name in the error; used by the program's argument parsing.
double parse_non_negative(const std::string& option, const std::string& text);

}  // namespace robodds::wan
