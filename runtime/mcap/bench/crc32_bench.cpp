// CRC-32 throughput over buffers of a message's size up to a chunk's (1 MiB), in bytes/s. The
// writer checks every byte twice (a chunk's records, then the data section), so this bounds how
// fast a recorder can write. docs/performance.md, "Recording in the run (issue 25)".
#include <benchmark/benchmark.h>

#include <cstdint>
#include <vector>

#include "runtime/mcap/crc32.hpp"

namespace {

void BM_Crc32(benchmark::State& state) {
  std::vector<std::uint8_t> data(static_cast<std::size_t>(state.range(0)));
  for (std::size_t i = 0; i < data.size(); ++i) data[i] = static_cast<std::uint8_t>(i * 131 + 7);
  std::uint32_t crc = 0;
  for (auto _ : state) {
    crc = robodds::mcap::crc32_update(crc, data.data(), data.size());
    benchmark::DoNotOptimize(crc);
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) * state.range(0));
}

BENCHMARK(BM_Crc32)->Arg(100)->Arg(4096)->Arg(1 << 20);

}  // namespace

BENCHMARK_MAIN();
