// robodds-mcap-sample-writer OUT_DIR: writes MCAP files with our writer for the integration tests
// that check them with `robodds info` and with the official reader (tests/npm/check_mcap.mjs):
//   sample_none.mcap, sample_zstd.mcap, sample_lz4.mcap: small chunks (several per file), a channel
//     of opaque bytes (no schema) and an omgidl channel whose three samples are hand-encoded XCDR1
//     (little-endian, 4-byte encapsulation header): nested struct, sequences, string, double, enum;
//   sample_empty.mcap: a schema and a channel, no message;
//   sample_expect.json: what those three samples must decode to.
// A test tool: built with the tests, not installed.
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "runtime/mcap/mcap_writer.hpp"

namespace {

// The schema, as a recorder would store it (schema encoding "omgidl", name the qualified type).
const char* const kIdl = R"(module robodds_test {
  enum Mode { IDLE, DRIVING, FAULT };
  struct Vec2 {
    double x;
    double y;
  };
  struct Sample {
    string name;
    Vec2 position;
    sequence<double> ranges;
    Mode mode;
    double stamp;
    sequence<Vec2> path;
  };
};
)";

/// XCDR1 little-endian by hand: primitives aligned to their size, counted from the end of the
/// encapsulation header (which is why `body` starts after it).
class Cdr {
 public:
  Cdr() : bytes_{0x00, 0x01, 0x00, 0x00} {}  // CDR_LE encapsulation, options 0
  void u32(std::uint32_t v) { put(&v, 4); }
  void f64(double v) { put(&v, 8); }
  void str(const std::string& s) {
    u32(static_cast<std::uint32_t>(s.size() + 1));  // length counts the terminating NUL
    bytes_.insert(bytes_.end(), s.begin(), s.end());
    bytes_.push_back(0);
  }
  const std::vector<std::uint8_t>& bytes() const { return bytes_; }

 private:
  void put(const void* v, std::size_t size) {
    while ((bytes_.size() - 4) % size != 0) bytes_.push_back(0);  // padding
    const auto* p = static_cast<const std::uint8_t*>(v);  // the host is little-endian (x86-64, arm64)
    bytes_.insert(bytes_.end(), p, p + size);
  }
  std::vector<std::uint8_t> bytes_;
};

struct Vec2 {
  double x, y;
};
struct Sample {
  std::string name;
  Vec2 position;
  std::vector<double> ranges;
  std::uint32_t mode;
  double stamp;
  std::vector<Vec2> path;
};

std::vector<std::uint8_t> encode(const Sample& s) {
  Cdr c;
  c.str(s.name);
  c.f64(s.position.x);
  c.f64(s.position.y);
  c.u32(static_cast<std::uint32_t>(s.ranges.size()));
  for (double r : s.ranges) c.f64(r);
  c.u32(s.mode);
  c.f64(s.stamp);
  c.u32(static_cast<std::uint32_t>(s.path.size()));
  for (const Vec2& p : s.path) {
    c.f64(p.x);
    c.f64(p.y);
  }
  return c.bytes();
}

std::string number(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string json(const Sample& s) {
  auto vec2 = [](const Vec2& v) { return "{\"x\":" + number(v.x) + ",\"y\":" + number(v.y) + "}"; };
  std::string out = "{\"name\":\"" + s.name + "\",\"position\":" + vec2(s.position) + ",\"ranges\":[";
  for (std::size_t i = 0; i < s.ranges.size(); ++i) out += (i ? "," : "") + number(s.ranges[i]);
  out += "],\"mode\":" + std::to_string(s.mode) + ",\"stamp\":" + number(s.stamp) + ",\"path\":[";
  for (std::size_t i = 0; i < s.path.size(); ++i) out += (i ? "," : "") + vec2(s.path[i]);
  return out + "]}";
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: robodds-mcap-sample-writer OUT_DIR\n";
    return 2;
  }
  const std::string dir = argv[1];
  const std::vector<Sample> samples = {
      {"robot_1", {1.5, -2.25}, {0.5, 1.0, 2.5}, 1, 12.5, {{0.0, 0.0}, {3.0, 4.0}}},
      {"", {0.1, 1e-300}, {}, 0, 1e10, {}},
      {"robot_2 with a longer name", {-7.75, 123456.789}, {3.141592653589793}, 2, 99.125, {{-1.0, 2.0}}},
  };
  // Times of the omgidl samples, spread over the file: 1 s, 2 s, 3 s (ns).
  const std::uint64_t sample_times[3] = {1000000000ULL, 2000000000ULL, 3000000000ULL};
  try {
    for (const char* compression : {"none", "zstd", "lz4"}) {
      robodds::mcap::WriterOptions options;
      options.compression = robodds::mcap::parse_compression(compression, "compression");
      options.chunk_size_bytes = 4096;  // several chunks per file
      robodds::mcap::Writer writer(dir + "/sample_" + compression + ".mcap", options);
      const std::uint16_t schema = writer.add_schema("robodds_test::Sample", "omgidl", kIdl);
      const std::uint16_t sample_channel = writer.add_channel(schema, "test/sample", "cdr", {{"origin", "robodds-mcap-sample-writer"}});
      const std::uint16_t bytes_channel = writer.add_channel(0, "test/bytes", "");
      std::size_t next_sample = 0;
      for (std::uint32_t i = 0; i < 400; ++i) {
        const std::uint64_t t = 10000000ULL * i;  // 100 Hz over 4 s
        while (next_sample < samples.size() && sample_times[next_sample] <= t) {
          const std::vector<std::uint8_t> cdr = encode(samples[next_sample]);
          writer.write(sample_channel, static_cast<std::uint32_t>(next_sample), sample_times[next_sample],
                       sample_times[next_sample] - 500, cdr.data(), cdr.size());
          ++next_sample;
        }
        std::uint8_t payload[64];
        for (std::size_t k = 0; k < sizeof payload; ++k) payload[k] = static_cast<std::uint8_t>(i + k);
        writer.write(bytes_channel, i, t, t, payload, sizeof payload);
      }
      writer.close();
    }
    {
      // No messages: a schema and a channel, no chunk (a recorder stopped before any sample).
      robodds::mcap::Writer writer(dir + "/sample_empty.mcap", robodds::mcap::WriterOptions{});
      writer.add_channel(writer.add_schema("robodds_test::Sample", "omgidl", kIdl), "test/sample", "cdr");
      writer.close();
    }
    std::ofstream expect(dir + "/sample_expect.json");
    expect << "[\n";
    for (std::size_t i = 0; i < samples.size(); ++i) {
      expect << "{\"topic\":\"test/sample\",\"log_time\":\"" << sample_times[i] << "\",\"publish_time\":\""
             << sample_times[i] - 500 << "\",\"value\":" << json(samples[i]) << "}" << (i + 1 < samples.size() ? "," : "")
             << "\n";
    }
    expect << "]\n";
    if (!expect) throw std::runtime_error(dir + "/sample_expect.json: cannot write");
  } catch (const std::exception& e) {
    std::cerr << "robodds-mcap-sample-writer: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
