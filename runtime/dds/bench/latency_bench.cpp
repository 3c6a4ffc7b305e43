// latency_bench: one-hop latency of robodds::idl::RobotState, raw Fast DDS vs the robodds runtime.
//
//   latency_bench raw|runtime|cv colocated|processes [--samples N] [--warmup N] [--domain D]
//                 [--qos FILE] [--profile state|lockstep|...] [--participant-profile NAME]
//                 [--security DIR]
//
// A pinger writes a sample on bench/ping; a ponger echoes it on bench/pong; one hop is half
// the round trip measured by the pinger (steady_clock before write(), after its waiting
// thread has the echo). Both sides wait on a condition variable that the reader's listener
// signals, i.e. every hop includes a thread wake-up, as in a component.
//
//   raw      plain DataWriter/DataReader; the listener take_next_sample()s into a buffer,
//            stores it under a mutex and notifies a condition variable. No runtime code.
//   runtime  make_dds_bus(), Bus::writer/reader, Output<RobotState>::publish() and a reader
//            callback feeding Input<RobotState>::on_sample(); the waiting thread uses the
//            runtime's Notifier and Input::take_new(), exactly the component path.
//   cv       no DDS: the same exchange through a mutex + condition variable mailbox (colocated
//            only), the floor set by two thread hand-offs per round trip on this machine.
//   colocated  ONE DomainParticipant (robodds co-locates components on one bus), the pinger on
//            the main thread and the ponger on a second thread. Raw colocated also uses one
//            participant so that both go through Fast DDS's intra-process delivery.
//   processes  this binary re-executes itself as the ponger (--role ponger): one participant
//            per process (shared-memory transport with the default participant profile).
//            `--role pinger` skips the spawn and waits for a ponger started by hand (another
//            host: give both the same --domain, and --participant-profile robodds.participant.udp_only
//            where shared memory is not shared).
//
// --security DIR (runtime only): both participants use DDS Security with the files of DIR/bench/
//            (docs/security.md, "Cost": an identity whose permissions allow bench/ping and bench/pong).
//
// Output, one line per configuration (times in microseconds, one hop):
//   latency raw colocated state participants=1 samples=20000 median_us=.. p90_us=.. p99_us=.. max_us=..
// Exit status: 0 ok, 2 bad arguments or QoS file, 3 the peer never matched / stopped answering,
// 1 any other error.

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/Topic.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "robodds/idl/robodds.h"
#include "robodds/idl/roboddsPubSubTypes.h"
#include "runtime/dds/dds_bus.hpp"
#include "runtime/base/error.hpp"
#include "runtime/io/io.hpp"
#include "runtime/base/log.hpp"
#include "runtime/io/notifier.hpp"
#include "runtime/bus/qos_profiles.hpp"

#ifndef ROBODDS_SOURCE_DIR
#define ROBODDS_SOURCE_DIR "."
#endif

namespace {

namespace dds = eprosima::fastdds::dds;
using eprosima::fastrtps::types::ReturnCode_t;
using robodds::idl::RobotState;
using Clock = std::chrono::steady_clock;

constexpr const char* kPingTopic = "bench/ping";
constexpr const char* kPongTopic = "bench/pong";
constexpr std::uint32_t kRobotId = 7;
constexpr std::uint64_t kStop = std::numeric_limits<std::uint64_t>::max();  // next_step of the last ping
constexpr auto kMatchTimeout = std::chrono::seconds(5);
constexpr auto kReplyTimeout = std::chrono::seconds(2);    // per ping once matched
constexpr auto kPongerIdle = std::chrono::seconds(10);     // ponger gives up after this silence
constexpr auto kHandshakeRetry = std::chrono::milliseconds(20);

/// The peer did not match or stopped answering (exit status 3).
class PeerError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};
/// Bad arguments or QoS file (exit status 2).
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Options {
  std::string impl;    // raw | runtime
  std::string deploy;  // colocated | processes
  std::string role;  // "" = spawn the ponger; "pinger"/"ponger": one side only (processes)
  int samples = 20000;
  int warmup = 1000;
  int domain = -1;
  std::string qos_file = std::string(ROBODDS_SOURCE_DIR) + "/deploy/qos/robodds_qos.xml";
  std::string profile = robodds::kStateProfile;
  std::string participant_profile = robodds::kDefaultParticipantProfile;
  std::string security_dir;  // runtime only: DDS Security with DIR/bench/ ("" = none)
};

/// One side of the exchange: writes on one topic, waits for samples on the other.
class Link {
 public:
  virtual ~Link() = default;
  /// Writes `sample` (header.step = its sequence number); final = the last one (stop signal).
  virtual void send(RobotState& sample, bool final) = 0;
  /// Waits for a sample newer than the last one returned; false at the deadline.
  virtual bool receive(RobotState* out, Clock::time_point deadline) = 0;
};

// ------------------------------------------------------------------------------------------
// raw Fast DDS

class RawParticipant {
 public:
  RawParticipant(const Options& o, const std::string& name) {
    auto* factory = dds::DomainParticipantFactory::get_instance();
    if (factory->load_XML_profiles_file(o.qos_file) != ReturnCode_t::RETCODE_OK) {
      throw UsageError(o.qos_file + ": rejected by Fast DDS or not readable");
    }
    dds::DomainParticipantQos qos;
    if (factory->get_participant_qos_from_profile(o.participant_profile, qos) != ReturnCode_t::RETCODE_OK) {
      throw UsageError(o.qos_file + ": no participant profile '" + o.participant_profile + "'");
    }
    qos.name(name);
    participant_ = factory->create_participant(o.domain, qos);
    if (participant_ == nullptr) {
      throw std::runtime_error("cannot create a participant on domain " + std::to_string(o.domain));
    }
    auto* type = new robodds::idl::RobotStatePubSubType();
    type->auto_fill_type_object(false);  // as runtime/dds/type_support.cpp
    type->auto_fill_type_information(false);
    type_ = dds::TypeSupport(type);
    type_.register_type(participant_);
    publisher_ = participant_->create_publisher(dds::PUBLISHER_QOS_DEFAULT);
    subscriber_ = participant_->create_subscriber(dds::SUBSCRIBER_QOS_DEFAULT);
  }
  ~RawParticipant() {
    participant_->delete_contained_entities();
    dds::DomainParticipantFactory::get_instance()->delete_participant(participant_);
  }
  dds::Topic* topic(const std::string& name) {
    for (dds::Topic* t : topics_) {
      if (t->get_name() == name) {
        return t;
      }
    }
    dds::Topic* t = participant_->create_topic(name, type_.get_type_name(), dds::TOPIC_QOS_DEFAULT);
    if (t == nullptr) {
      throw std::runtime_error("cannot create topic " + name);
    }
    topics_.push_back(t);
    return t;
  }
  dds::Publisher* publisher() const { return publisher_; }
  dds::Subscriber* subscriber() const { return subscriber_; }

 private:
  dds::DomainParticipant* participant_ = nullptr;
  dds::TypeSupport type_;
  dds::Publisher* publisher_ = nullptr;
  dds::Subscriber* subscriber_ = nullptr;
  std::vector<dds::Topic*> topics_;
};

class RawLink : public Link, private dds::DataReaderListener {
 public:
  RawLink(RawParticipant& p, const std::string& out, const std::string& in, const std::string& profile) {
    writer_ = p.publisher()->create_datawriter_with_profile(p.topic(out), profile);
    if (writer_ == nullptr) {
      throw UsageError("cannot create a writer on " + out + " with QoS profile '" + profile + "'");
    }
    reader_ = p.subscriber()->create_datareader_with_profile(p.topic(in), profile, this, dds::StatusMask::data_available());
    if (reader_ == nullptr) {
      throw UsageError("cannot create a reader on " + in + " with QoS profile '" + profile + "'");
    }
  }

  void send(RobotState& sample, bool final) override {
    sample.header().next_step(final ? kStop : sample.header().step() + 1);
    if (!writer_->write(&sample)) {
      throw std::runtime_error("DataWriter::write failed");
    }
  }

  bool receive(RobotState* out, Clock::time_point deadline) override {
    std::unique_lock<std::mutex> lock(mutex_);
    if (!cv_.wait_until(lock, deadline, [this] { return fresh_; })) {
      return false;
    }
    *out = latest_;
    fresh_ = false;
    return true;
  }

 private:
  void on_data_available(dds::DataReader* reader) override {
    dds::SampleInfo info;
    while (reader->take_next_sample(&buffer_, &info) == ReturnCode_t::RETCODE_OK) {
      if (!info.valid_data) {
        continue;
      }
      {
        std::lock_guard<std::mutex> lock(mutex_);
        latest_ = buffer_;
        fresh_ = true;
      }
      cv_.notify_one();
    }
  }

  dds::DataWriter* writer_ = nullptr;
  dds::DataReader* reader_ = nullptr;
  RobotState buffer_;
  std::mutex mutex_;
  std::condition_variable cv_;
  RobotState latest_;
  bool fresh_ = false;
};

// ------------------------------------------------------------------------------------------
// robodds runtime

class RuntimeLink : public Link {
 public:
  RuntimeLink(robodds::Bus& bus, const std::string& out, const std::string& in, const std::string& profile,
              const std::string& owner)
      : input_(in, owner, &state_, &notifier_, input_options()),
        output_(bus.writer(out, robodds::idl::type_name<RobotState>(), profile), &state_) {
    robodds::Input<RobotState>* raw = &input_;
    reader_ = bus.reader(
        in, robodds::idl::type_name<RobotState>(), profile,
        [raw](const void* sample, const robodds::SampleMeta& meta) { raw->on_sample(*static_cast<const RobotState*>(sample), meta); },
        [owner, in](const std::string& event) { robodds::log::warn(owner, in + ": " + event); });
  }

  void send(RobotState& sample, bool final) override {
    state_.step = sample.header().step();
    if (final) {
      output_.publish_final(sample);
    } else {
      output_.publish(sample);
    }
  }

  bool receive(RobotState* out, Clock::time_point deadline) override {
    for (;;) {
      const std::uint64_t seen = notifier_.generation();
      std::vector<RobotState> samples = input_.take_new(kRobotId);
      if (!samples.empty()) {
        *out = std::move(samples.back());
        return true;
      }
      const auto now = Clock::now();
      if (now >= deadline) {
        return false;
      }
      notifier_.wait(seen, std::chrono::duration_cast<std::chrono::microseconds>(deadline - now));
    }
  }

 private:
  static robodds::detail::InputOptions input_options() {
    robodds::detail::InputOptions o;
    o.expected = {kRobotId};
    o.key_names = "robot_id";
    return o;
  }

  // Real-time mode: the Input hands over every sample as it arrives (no step gating).
  robodds::StepState state_{0, 1, 0, robodds::TimeMode::kRealtime};
  robodds::Notifier notifier_;
  robodds::Input<RobotState> input_;
  robodds::Output<RobotState> output_;
  std::shared_ptr<robodds::ReaderHandle> reader_;
};

// ------------------------------------------------------------------------------------------
// cv: no DDS at all, the floor of a thread hand-off (colocated only)

struct Mailbox {
  std::mutex mutex;
  std::condition_variable cv;
  RobotState latest;
  bool fresh = false;
};

class CvLink : public Link {
 public:
  CvLink(Mailbox& out, Mailbox& in) : out_(out), in_(in) {}
  void send(RobotState& sample, bool final) override {
    sample.header().next_step(final ? kStop : sample.header().step() + 1);
    {
      std::lock_guard<std::mutex> lock(out_.mutex);
      out_.latest = sample;
      out_.fresh = true;
    }
    out_.cv.notify_one();
  }
  bool receive(RobotState* out, Clock::time_point deadline) override {
    std::unique_lock<std::mutex> lock(in_.mutex);
    if (!in_.cv.wait_until(lock, deadline, [this] { return in_.fresh; })) {
      return false;
    }
    *out = in_.latest;
    in_.fresh = false;
    return true;
  }

 private:
  Mailbox& out_;
  Mailbox& in_;
};

std::unique_ptr<robodds::DdsBus> make_bus(const Options& o, const std::string& name) {
  robodds::DdsOptions d;
  d.domain_id = o.domain;
  d.qos_files = {o.qos_file};
  d.participant_profile = o.participant_profile;
  d.participant_name = name;
  d.security_dir = o.security_dir;
  d.security_identity = "bench";
  try {
    return robodds::make_dds_bus(d);
  } catch (const robodds::ConfigError& e) {
    throw UsageError(e.what());
  }
}

// ------------------------------------------------------------------------------------------
// the exchange

RobotState make_sample(std::uint64_t seq) {
  RobotState s;
  s.robot_id(kRobotId);
  s.header().step(seq);
  s.header().stamp_ns(static_cast<std::int64_t>(seq) * 10000000);
  s.x(1.5);
  s.y(-2.25);
  s.theta(0.75);
  s.v(0.5);
  s.omega(0.1);
  return s;
}

/// Echoes pings until the stop ping, or until `stop` is set, or after a silence.
void pong_loop(Link& link, const std::atomic<bool>* stop, bool standalone) {
  bool first = true;
  auto last_ping = Clock::now();
  RobotState sample;
  for (;;) {
    if (stop != nullptr && stop->load()) {
      return;
    }
    if (!link.receive(&sample, Clock::now() + std::chrono::milliseconds(100))) {
      const auto silence = Clock::now() - last_ping;
      if (standalone && first && silence > kMatchTimeout) {
        throw PeerError("ponger: no ping within 5 s: the pinger never matched (same --domain, --qos, --profile?)");
      }
      if (silence > kPongerIdle) {
        throw PeerError("ponger: no ping for 10 s, giving up");
      }
      continue;
    }
    first = false;
    last_ping = Clock::now();
    if (sample.header().next_step() == kStop) {
      return;
    }
    link.send(sample, false);
  }
}

/// `alive` is polled while matching (a child process that died is reported at once).
std::vector<double> ping_loop(Link& link, const Options& o, const std::function<void()>& alive) {
  std::uint64_t seq = 0;
  RobotState sample;
  // Handshake: a volatile profile drops samples written before the peer matched, so ping
  // every 20 ms until one echo of the current ping comes back (both directions matched).
  const auto match_deadline = Clock::now() + kMatchTimeout;
  for (bool matched = false; !matched;) {
    if (Clock::now() > match_deadline) {
      throw PeerError("pinger: no echo within 5 s: the ponger never matched (domain " + std::to_string(o.domain) +
                      ", profile " + o.profile + ")");
    }
    alive();
    RobotState ping = make_sample(++seq);
    link.send(ping, false);
    const auto retry = Clock::now() + kHandshakeRetry;
    while (link.receive(&sample, retry)) {
      if (sample.header().step() == seq) {
        matched = true;
        break;
      }
    }
  }
  std::vector<double> hops;
  hops.reserve(static_cast<std::size_t>(o.samples));
  for (int i = 0; i < o.warmup + o.samples; ++i) {
    RobotState ping = make_sample(++seq);
    const auto t0 = Clock::now();
    link.send(ping, false);
    const auto deadline = t0 + kReplyTimeout;
    for (;;) {
      if (!link.receive(&sample, deadline)) {
        throw PeerError("pinger: no echo of ping " + std::to_string(i) + " within 2 s (peer gone?)");
      }
      if (sample.header().step() == seq) {
        break;
      }
    }
    const auto t1 = Clock::now();
    if (i >= o.warmup) {
      hops.push_back(std::chrono::duration<double, std::micro>(t1 - t0).count() / 2.0);
    }
  }
  RobotState stop = make_sample(++seq);
  link.send(stop, true);
  return hops;
}

double percentile(const std::vector<double>& sorted, double p) {
  if (sorted.empty()) {
    return 0.0;
  }
  const auto rank = static_cast<std::size_t>(std::ceil(p * static_cast<double>(sorted.size())));
  return sorted[std::min(sorted.size() - 1, rank == 0 ? 0 : rank - 1)];
}

void report(const Options& o, int participants, std::vector<double> hops) {
  std::sort(hops.begin(), hops.end());
  std::printf("latency %s %s %s participants=%d samples=%zu median_us=%.2f p90_us=%.2f p99_us=%.2f max_us=%.2f\n",
              o.impl.c_str(), o.deploy.c_str(), o.profile.c_str(), participants, hops.size(), percentile(hops, 0.5),
              percentile(hops, 0.9), percentile(hops, 0.99), hops.empty() ? 0.0 : hops.back());
  std::fflush(stdout);
}

std::string self_exe() {
  char buf[4096];
  const ssize_t n = readlink("/proc/self/exe", buf, sizeof(buf) - 1);
  if (n <= 0) {
    throw std::runtime_error("cannot read /proc/self/exe");
  }
  buf[n] = '\0';
  return buf;
}

/// The ponger child process; killed with its parent.
class Child {
 public:
  explicit Child(const Options& o) {
    std::vector<std::string> args = {self_exe(), o.impl, o.deploy, "--role", "ponger", "--domain", std::to_string(o.domain),
                                     "--qos", o.qos_file, "--profile", o.profile, "--participant-profile",
                                     o.participant_profile, "--security", o.security_dir};
    std::fflush(stdout);
    std::fflush(stderr);
    const pid_t parent = getpid();
    pid_ = fork();
    if (pid_ < 0) {
      throw std::runtime_error("fork failed");
    }
    if (pid_ == 0) {
      prctl(PR_SET_PDEATHSIG, SIGKILL);
      if (getppid() != parent) {
        _exit(1);
      }
      std::vector<char*> argv;
      for (std::string& a : args) {
        argv.push_back(a.data());
      }
      argv.push_back(nullptr);
      execv(argv[0], argv.data());
      std::perror("latency_bench: execv");
      _exit(127);
    }
  }
  ~Child() {
    if (pid_ > 0) {
      kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
    }
  }
  /// Throws if the child has already exited.
  void check_alive() {
    int status = 0;
    if (pid_ > 0 && waitpid(pid_, &status, WNOHANG) == pid_) {
      pid_ = -1;
      throw PeerError("pinger: the ponger process exited early (" + describe(status) + ")");
    }
  }
  /// Waits up to `timeout` for a clean exit; false (and kills it) otherwise.
  bool wait(std::chrono::milliseconds timeout) {
    const auto deadline = Clock::now() + timeout;
    while (Clock::now() < deadline) {
      int status = 0;
      if (waitpid(pid_, &status, WNOHANG) == pid_) {
        pid_ = -1;
        return WIFEXITED(status) && WEXITSTATUS(status) == 0;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return false;
  }

 private:
  static std::string describe(int status) {
    if (WIFEXITED(status)) {
      return "exit status " + std::to_string(WEXITSTATUS(status));
    }
    if (WIFSIGNALED(status)) {
      return "signal " + std::to_string(WTERMSIG(status));
    }
    return "status " + std::to_string(status);
  }
  pid_t pid_ = -1;
};

void run_colocated(const Options& o) {
  std::vector<double> hops;
  std::atomic<bool> stop{false};
  std::exception_ptr ponger_error;
  auto exchange = [&](Link& pinger, Link& ponger) {
    std::thread thread([&] {
      try {
        pong_loop(ponger, &stop, false);
      } catch (...) {
        ponger_error = std::current_exception();
      }
    });
    try {
      hops = ping_loop(pinger, o, [] {});
    } catch (...) {
      stop = true;
      thread.join();
      throw;
    }
    thread.join();
    if (ponger_error) {
      std::rethrow_exception(ponger_error);
    }
  };
  // Links are declared before the participant/bus so that the DDS readers (whose listeners and
  // callbacks point into the links) are deleted first.
  std::unique_ptr<Link> ping;
  std::unique_ptr<Link> pong;
  Mailbox ping_box;
  Mailbox pong_box;
  int participants = 1;
  if (o.impl == "cv") {
    participants = 0;
    ping = std::make_unique<CvLink>(ping_box, pong_box);
    pong = std::make_unique<CvLink>(pong_box, ping_box);
    exchange(*ping, *pong);
  } else if (o.impl == "raw") {
    auto participant = std::make_unique<RawParticipant>(o, "latency_bench");
    ping = std::make_unique<RawLink>(*participant, kPingTopic, kPongTopic, o.profile);
    pong = std::make_unique<RawLink>(*participant, kPongTopic, kPingTopic, o.profile);
    exchange(*ping, *pong);
  } else {
    std::unique_ptr<robodds::DdsBus> bus = make_bus(o, "latency_bench");
    ping = std::make_unique<RuntimeLink>(*bus, kPingTopic, kPongTopic, o.profile, "pinger");
    pong = std::make_unique<RuntimeLink>(*bus, kPongTopic, kPingTopic, o.profile, "ponger");
    bus->start();
    exchange(*ping, *pong);
  }
  report(o, participants, std::move(hops));
}

void run_processes(const Options& o) {
  const bool ponger = o.role == "ponger";
  const std::string name = ponger ? "latency_bench-ponger" : "latency_bench-pinger";
  const std::string out = ponger ? kPongTopic : kPingTopic;
  const std::string in = ponger ? kPingTopic : kPongTopic;
  std::unique_ptr<Link> link;  // declared first: destroyed after the participant/bus
  std::unique_ptr<RawParticipant> participant;
  std::unique_ptr<robodds::DdsBus> bus;
  if (o.impl == "raw") {
    participant = std::make_unique<RawParticipant>(o, name);
    link = std::make_unique<RawLink>(*participant, out, in, o.profile);
  } else {
    bus = make_bus(o, name);
    link = std::make_unique<RuntimeLink>(*bus, out, in, o.profile, ponger ? "ponger" : "pinger");
    bus->start();
  }
  if (ponger) {
    pong_loop(*link, nullptr, true);
    return;
  }
  if (o.role == "pinger") {  // the ponger runs elsewhere (e.g. another host): --role ponger
    std::vector<double> hops = ping_loop(*link, o, [] {});
    report(o, 2, std::move(hops));
    return;
  }
  Child child(o);
  std::vector<double> hops = ping_loop(*link, o, [&] { child.check_alive(); });
  if (!child.wait(std::chrono::seconds(5))) {
    std::fprintf(stderr, "latency_bench: warning: the ponger did not exit cleanly after the stop ping\n");
  }
  report(o, 2, std::move(hops));
}

[[noreturn]] void usage(const std::string& why) {
  throw UsageError(why +
                   "\nusage: latency_bench raw|runtime|cv colocated|processes [--samples N] [--warmup N] [--domain D] "
                   "[--qos FILE] [--profile state|lockstep] [--participant-profile NAME] [--security DIR] [--role pinger|ponger]");
}

Options parse(int argc, char** argv) {
  Options o;
  std::vector<std::string> positional;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        usage(a + " needs a value");
      }
      return argv[++i];
    };
    auto number = [&](int lo, int hi) {
      const std::string v = value();
      try {
        std::size_t used = 0;
        const int n = std::stoi(v, &used);
        if (used == v.size() && n >= lo && n <= hi) {
          return n;
        }
      } catch (const std::exception&) {
      }
      usage(a + ": expected an integer in " + std::to_string(lo) + ".." + std::to_string(hi) + ", got '" + v + "'");
    };
    if (a == "--samples") {
      o.samples = number(1, 100000000);
    } else if (a == "--warmup") {
      o.warmup = number(0, 100000000);
    } else if (a == "--domain") {
      o.domain = number(0, 232);
    } else if (a == "--qos") {
      o.qos_file = value();
    } else if (a == "--profile") {
      o.profile = value();
    } else if (a == "--participant-profile") {
      o.participant_profile = value();
    } else if (a == "--security") {
      o.security_dir = value();
    } else if (a == "--role") {
      o.role = value();
      if (o.role != "pinger" && o.role != "ponger") {
        usage("--role: pinger or ponger");
      }
    } else if (a == "-h" || a == "--help") {
      usage("latency_bench: one-hop RobotState latency (half a ping-pong round trip)");
    } else if (!a.empty() && a[0] == '-') {
      usage("unknown option " + a);
    } else {
      positional.push_back(a);
    }
  }
  if (positional.size() != 2) {
    usage("expected two arguments");
  }
  o.impl = positional[0];
  o.deploy = positional[1];
  if (o.impl != "raw" && o.impl != "runtime" && o.impl != "cv") {
    usage("first argument: raw or runtime (or cv), got '" + o.impl + "'");
  }
  if (o.impl == "cv" && o.deploy != "colocated") {
    usage("cv (no DDS, the thread hand-off floor) is colocated only");
  }
  if (o.deploy != "colocated" && o.deploy != "processes") {
    usage("second argument: colocated or processes, got '" + o.deploy + "'");
  }
  if (!o.security_dir.empty() && o.impl != "runtime") {
    usage("--security is only for the runtime implementation");
  }
  if (!o.role.empty() && o.deploy != "processes") {
    usage("--role is only for processes mode");
  }
  if (o.domain < 0) {
    o.domain = 100 + static_cast<int>(getpid() % 100);  // away from robodds runs on domain 0
  }
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Options o = parse(argc, argv);
    if (o.deploy == "colocated") {
      run_colocated(o);
    } else {
      run_processes(o);
    }
    return 0;
  } catch (const UsageError& e) {
    std::fprintf(stderr, "latency_bench: %s\n", e.what());
    return 2;
  } catch (const robodds::ConfigError& e) {
    std::fprintf(stderr, "latency_bench: %s\n", e.what());
    return 2;
  } catch (const PeerError& e) {
    std::fprintf(stderr, "latency_bench: %s\n", e.what());
    return 3;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "latency_bench: error: %s\n", e.what());
    return 1;
  }
}
