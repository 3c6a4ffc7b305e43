// MCAP writer throughput: 100-byte messages on 10 channels into 1 MiB chunks, per compression.
// Reports bytes/s (message payload) and messages/s; the file goes to $TMPDIR (default /tmp) and is
// removed. docs/performance.md, "MCAP writer (issue 25)".
#include <benchmark/benchmark.h>

#include <unistd.h>

#include <cstdlib>
#include <string>
#include <vector>

#include "runtime/mcap/mcap_writer.hpp"

namespace {

using robodds::mcap::Compression;

void BM_McapWrite(benchmark::State& state) {
  const auto compression = static_cast<Compression>(state.range(0));
  const char* tmp = std::getenv("TMPDIR");
  const std::string path = std::string(tmp != nullptr ? tmp : "/tmp") + "/mcap_writer_bench." + std::to_string(::getpid()) + ".mcap";
  // A payload like a robot sample: a CDR header, a counter, doubles that change slowly.
  std::vector<std::uint8_t> payload(100);
  constexpr std::size_t kBatch = 100000;  // messages per iteration: 10 MB, several chunks
  std::uint64_t time_ns = 0;
  std::int64_t file_bytes = 0;
  for (auto _ : state) {
    robodds::mcap::WriterOptions options;
    options.compression = compression;
    robodds::mcap::Writer writer(path, options);
    const std::uint16_t schema = writer.add_schema("bench::Sample", "omgidl", "module bench { struct Sample { double v[12]; }; };");
    std::uint16_t channels[10];
    for (int c = 0; c < 10; ++c) channels[c] = writer.add_channel(schema, "bench/channel_" + std::to_string(c), "cdr");
    for (std::size_t i = 0; i < kBatch; ++i) {
      payload[4] = static_cast<std::uint8_t>(i);
      payload[5] = static_cast<std::uint8_t>(i >> 8);
      payload[20 + (i % 80)] = static_cast<std::uint8_t>(i / 7);
      time_ns += 1000000;  // 1 kHz in total
      writer.write(channels[i % 10], static_cast<std::uint32_t>(i), time_ns, time_ns, payload.data(), payload.size());
    }
    writer.close();
    file_bytes = static_cast<std::int64_t>(writer.file_bytes());
  }
  ::unlink(path.c_str());
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) * kBatch * 100);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * kBatch);
  state.counters["file_MB"] = static_cast<double>(file_bytes) / 1e6;
}

BENCHMARK(BM_McapWrite)
    ->Arg(static_cast<int>(Compression::kNone))
    ->Arg(static_cast<int>(Compression::kZstd))
    ->Arg(static_cast<int>(Compression::kLz4))
    ->ArgName("compression(0=none,1=zstd,2=lz4)")
    ->UseRealTime()  // a recorder must keep up in wall time (write(2) included), not only in CPU time
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
