// robodds-writer-delete-probe DOMAIN ROUNDS WRITERS: deletes reliable writers whose reader died.
// Each round forks a reader process (WRITERS topics, lockstep profile: reliable, KEEP_LAST 256),
// writes 16 x 256 samples on every writer, SIGKILLs the reader (its reader proxies stay matched until
// the lease ends, so the samples stay unacknowledged and the periodic heartbeat runs) and deletes
// the bus. With Fast DDS 2.9.1 a heartbeat during a writer's deletion can spin forever holding the
// writer's lock (Fast-DDS#4076; see FastDdsBus::clear_writer_histories): the shutdown watchdog then
// ends this process with its code 3. Exit 0: every round's bus was deleted.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>

#include "robodds/idl/robodds.h"
#include "runtime/dds/dds_bus.hpp"
#include "runtime/config/share_dir.hpp"

namespace {

robodds::DdsOptions options(int domain, const std::string& name) {
  robodds::DdsOptions o;
  o.domain_id = domain;
  o.qos_files.push_back(robodds::share_dir_of_this_process(ROBODDS_SOURCE_DIR) + "/" + robodds::kShareDirMarker);
  o.participant_name = name;
  return o;
}

std::string topic(int i) { return "probe/t" + std::to_string(i); }
const char* const kType = "robodds::idl::StepDone";

[[noreturn]] void reader_process(int domain, int writers) {
  auto bus = robodds::make_dds_bus(options(domain, "probe-reader"));
  for (int i = 0; i < writers; ++i) {
    bus->reader(topic(i), kType, "lockstep", [](const void*, const robodds::SampleMeta&) {}, nullptr);
  }
  bus->start();
  std::this_thread::sleep_for(std::chrono::seconds(60));  // the parent SIGKILLs it long before
  std::_Exit(0);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: %s DOMAIN ROUNDS WRITERS\n", argv[0]);
    return 2;
  }
  const int domain = std::atoi(argv[1]);
  const int rounds = std::atoi(argv[2]);
  const int writers = std::atoi(argv[3]);
  for (int round = 1; round <= rounds; ++round) {
    const pid_t child = fork();  // before this process creates any DDS entity of the round
    if (child == 0) {
      reader_process(domain, writers);
    }
    {
      auto bus = robodds::make_dds_bus(options(domain, "probe-writer"));
      std::vector<std::shared_ptr<robodds::WriterHandle>> handles;
      for (int i = 0; i < writers; ++i) {
        handles.push_back(bus->writer(topic(i), kType, "lockstep"));
      }
      bus->start();
      std::this_thread::sleep_for(std::chrono::milliseconds(1500));  // discovery and matching
      // 16 instances (keys) x 256 samples: a long history, so a deletion takes long enough for
      // a 10 ms heartbeat to fall inside it now and then.
      robodds::idl::StepDone sample;
      for (int n = 0; n < 256; ++n) {
        sample.components_run(static_cast<std::uint32_t>(n));
        for (int key = 0; key < 16; ++key) {
          sample.member("probe" + std::to_string(key));
          for (auto& handle : handles) {
            handle->write(&sample);
          }
        }
      }
      kill(child, SIGKILL);
      waitpid(child, nullptr, 0);
      for (int n = 0; n < 16; ++n) {  // samples no reader will ever acknowledge
        for (auto& handle : handles) {
          handle->write(&sample);
        }
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));  // heartbeats running
      const auto since = std::chrono::steady_clock::now();
      bus.reset();
      std::printf("round %d: deleted %d writers in %.3f s\n", round, writers,
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count());
      std::fflush(stdout);
    }
  }
  return 0;
}
