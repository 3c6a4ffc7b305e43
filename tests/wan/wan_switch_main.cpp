// robodds-wan-switch: joins network namespaces (test "hosts") through a user-space Ethernet
// switch whose links have a fixed one-way delay and a loss rate: a WAN on one machine, for the
// multi-host tests (tests/integration/netns_lib.sh, netns_setup_wan). This kernel has no netem.
//
//   robodds-wan-switch --delay-ms D [--loss P] [--seed S] --ready FILE [--stats FILE] NS...
//
// In every named namespace (ip netns, /var/run/netns/NS) it creates a TAP device eth0 and keeps
// its file descriptor: the devices live as long as this process. FILE is written once every
// device exists (the caller then configures addresses). SIGTERM/SIGINT end it; the per-port
// counters then go to --stats as JSON (and to stderr).
#include <fcntl.h>
#include <linux/if.h>
#include <linux/if_tun.h>
#include <poll.h>
#include <sched.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <ctime>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "tests/wan/delay_switch.hpp"

namespace {

volatile std::sig_atomic_t g_stop = 0;
void on_signal(int) { g_stop = 1; }

double monotonic_s() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

std::runtime_error system_error(const std::string& what) {
  return std::runtime_error(what + ": " + std::strerror(errno));
}

// Enters namespace `ns`, creates its TAP eth0 there, comes back to `home` (our own namespace).
int open_tap_in(const std::string& ns, int home) {
  const std::string path = "/var/run/netns/" + ns;
  const int ns_fd = open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (ns_fd < 0) throw system_error("namespace " + ns + " (" + path + ")");
  if (setns(ns_fd, CLONE_NEWNET) != 0) {
    close(ns_fd);
    throw system_error("entering namespace " + ns);
  }
  close(ns_fd);
  const int tap = open("/dev/net/tun", O_RDWR | O_NONBLOCK | O_CLOEXEC);
  const int open_errno = errno;
  ifreq request{};
  request.ifr_flags = IFF_TAP | IFF_NO_PI;
  std::strncpy(request.ifr_name, "eth0", IFNAMSIZ - 1);
  const bool made = tap >= 0 && ioctl(tap, TUNSETIFF, &request) == 0;
  const int make_errno = errno;
  if (setns(home, CLONE_NEWNET) != 0) throw system_error("returning to our own namespace");
  if (tap < 0) {
    errno = open_errno;
    throw system_error("/dev/net/tun");
  }
  if (!made) {
    close(tap);
    errno = make_errno;
    throw system_error("creating TAP eth0 in namespace " + ns);
  }
  return tap;
}

struct Options {
  robodds::wan::DelaySwitchParams params;
  std::string ready_file;
  std::string stats_file;
  std::vector<std::string> namespaces;
};

Options parse(int argc, char** argv) {
  Options options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(arg + ": needs a value");
      return argv[++i];
    };
    if (arg == "--delay-ms") {
      options.params.delay_s = 1e-3 * robodds::wan::parse_non_negative(arg, value());
    } else if (arg == "--loss") {
      options.params.loss = robodds::wan::parse_non_negative(arg, value());
    } else if (arg == "--seed") {
      options.params.seed = static_cast<std::uint64_t>(robodds::wan::parse_non_negative(arg, value()));
    } else if (arg == "--ready") {
      options.ready_file = value();
    } else if (arg == "--stats") {
      options.stats_file = value();
    } else if (!arg.empty() && arg[0] == '-') {
      throw std::invalid_argument("unknown option " + arg);
    } else {
      options.namespaces.push_back(arg);
    }
  }
  if (options.ready_file.empty()) throw std::invalid_argument("--ready FILE is required");
  if (options.namespaces.size() < 2) throw std::invalid_argument("name at least 2 namespaces");
  options.params.validate();
  return options;
}

void write_stats(std::ostream& out, const Options& options, const robodds::wan::DelaySwitch& sw) {
  out << "{\"delay_ms\": " << 1e3 * options.params.delay_s << ", \"loss\": " << options.params.loss
      << ", \"ports\": {";
  for (std::size_t p = 0; p < sw.ports(); ++p) {
    const auto& c = sw.counters(p);
    out << (p ? ", " : "") << '"' << options.namespaces[p] << "\": {\"frames_in\": " << c.frames_in
        << ", \"bytes_in\": " << c.bytes_in << ", \"frames_out\": " << c.frames_out
        << ", \"bytes_out\": " << c.bytes_out << ", \"lost\": " << c.lost
        << ", \"overflowed\": " << c.overflowed << '}';
  }
  out << "}}\n";
}

int run(const Options& options) {
  const int home = open("/proc/self/ns/net", O_RDONLY | O_CLOEXEC);
  if (home < 0) throw system_error("/proc/self/ns/net");
  std::vector<pollfd> taps;
  for (const auto& ns : options.namespaces) taps.push_back(pollfd{open_tap_in(ns, home), POLLIN, 0});
  close(home);
  robodds::wan::DelaySwitch sw(taps.size(), options.params);
  {
    std::ofstream ready(options.ready_file);
    ready << "ready\n";
    if (!ready) throw std::runtime_error("cannot write " + options.ready_file);
  }
  std::vector<std::uint8_t> buffer(65536);
  std::uint64_t write_errors = 0;
  while (!g_stop) {
    const double next = sw.next_due_s();
    timespec wait{1, 0};  // nothing queued: wake now and then to see a signal
    if (next >= 0.0) {
      const double left = std::max(0.0, next - monotonic_s());
      wait.tv_sec = static_cast<time_t>(left);
      wait.tv_nsec = static_cast<long>((left - static_cast<double>(wait.tv_sec)) * 1e9);
    }
    const int ready = ppoll(taps.data(), taps.size(), &wait, nullptr);
    if (ready < 0 && errno != EINTR) throw system_error("ppoll");
    const double now = monotonic_s();
    for (std::size_t p = 0; ready > 0 && p < taps.size(); ++p) {
      if ((taps[p].revents & POLLIN) == 0) continue;
      for (;;) {
        const ssize_t n = read(taps[p].fd, buffer.data(), buffer.size());
        if (n <= 0) break;  // EAGAIN: drained
        sw.receive(p, buffer.data(), static_cast<std::size_t>(n), now);
      }
    }
    for (const auto& due : sw.take_due(monotonic_s())) {
      if (write(taps[due.port].fd, due.frame.data(), due.frame.size()) < 0) ++write_errors;
    }
  }
  write_stats(std::cerr, options, sw);
  if (write_errors) std::cerr << "robodds-wan-switch: " << write_errors << " frames could not be written\n";
  if (!options.stats_file.empty()) {
    std::ofstream stats(options.stats_file);
    write_stats(stats, options, sw);
  }
  for (auto& tap : taps) close(tap.fd);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::signal(SIGTERM, on_signal);
  std::signal(SIGINT, on_signal);
  try {
    return run(parse(argc, argv));
  } catch (const std::exception& e) {
    std::cerr << "robodds-wan-switch: error: " << e.what() << '\n';
    return 2;
  }
}
