#include "runtime/mcap/mcap_info.hpp"

#include <algorithm>
#include <cstdio>
#include <set>
#include <sstream>

namespace robodds::mcap {
namespace {

std::string seconds(std::uint64_t ns) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%llu.%09llu s", static_cast<unsigned long long>(ns / 1000000000ULL),
                static_cast<unsigned long long>(ns % 1000000000ULL));
  return buf;
}

std::string fixed(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

std::string pad(const std::string& s, std::size_t width) { return s.size() >= width ? s : s + std::string(width - s.size(), ' '); }
std::string pad_left(const std::string& s, std::size_t width) {
  return s.size() >= width ? s : std::string(width - s.size(), ' ') + s;
}

}  // namespace

double channel_rate_hz(const ChannelCounts& counts) {
  if (counts.messages < 2 || counts.last_log_time <= counts.first_log_time) return 0.0;
  return static_cast<double>(counts.messages - 1) * 1e9 / static_cast<double>(counts.last_log_time - counts.first_log_time);
}

std::string format_info(const ReadReport& r) {
  std::ostringstream out;
  out << "file:         " << r.path << " (" << with_thousands(r.file_size) << " bytes)\n";
  out << "library:      " << (r.library.empty() ? "(none)" : r.library)
      << (r.profile.empty() ? "" : ", profile " + r.profile) << "\n";
  if (r.valid()) {
    out << "summary:      present, CRCs valid (chunks, data section, summary)\n";
  } else if (r.truncated_at) {
    out << "summary:      missing\n";
    out << "recovered:    " << r.recovery() << "\n";
  } else if (!r.summary_present) {
    out << "summary:      missing or damaged, " << r.problems.size() << (r.problems.size() == 1 ? " problem" : " problems")
        << " (below)\n";
  } else {
    out << "summary:      present, " << r.problems.size() << (r.problems.size() == 1 ? " problem" : " problems")
        << " (below)\n";
  }
  const Statistics& s = r.counted;
  std::map<std::string, std::uint64_t> by_compression;
  std::uint64_t compressed = 0, uncompressed = 0;
  for (const ChunkInfo& c : r.chunks) {
    ++by_compression[c.compression.empty() ? "none" : c.compression];
    compressed += c.compressed_size;
    uncompressed += c.uncompressed_size;
  }
  out << "chunks:       " << with_thousands(r.chunks.size());
  if (!r.chunks.empty()) {
    out << " (";
    bool first = true;
    for (const auto& [name, n] : by_compression) {
      out << (first ? "" : ", ") << name << (by_compression.size() > 1 ? " " + with_thousands(n) : "");
      first = false;
    }
    out << "), " << with_thousands(compressed) << " bytes stored for " << with_thousands(uncompressed) << " bytes of records";
  }
  out << "\n";
  out << "messages:     " << with_thousands(s.message_count) << "\n";
  if (s.message_count > 0) {
    out << "start:        " << seconds(s.message_start_time) << "\n";
    out << "end:          " << seconds(s.message_end_time) << "\n";
    out << "duration:     " << fixed(static_cast<double>(s.message_end_time - s.message_start_time) / 1e9, 3) << " s\n";
  }
  out << "channels:     " << r.channels.size() << "\n";
  if (!r.channels.empty()) {
    std::map<std::uint16_t, const SchemaInfo*> schemas;
    for (const SchemaInfo& schema : r.schemas) schemas[schema.id] = &schema;
    std::vector<std::vector<std::string>> rows{{"id", "topic", "schema", "schema encoding", "message encoding", "messages", "rate (Hz)"}};
    for (const ChannelInfo& c : r.channels) {
      const auto counts_it = r.channel_counts.find(c.id);
      const ChannelCounts counts = counts_it == r.channel_counts.end() ? ChannelCounts{} : counts_it->second;
      const auto schema_it = schemas.find(c.schema_id);
      const bool known = schema_it != schemas.end();
      const double rate = channel_rate_hz(counts);
      rows.push_back({std::to_string(c.id), c.topic, known ? schema_it->second->name : (c.schema_id == 0 ? "(none)" : "(missing)"),
                      known ? schema_it->second->encoding : "-", c.message_encoding.empty() ? "-" : c.message_encoding,
                      with_thousands(counts.messages), rate > 0 ? fixed(rate, 2) : "-"});
    }
    std::vector<std::size_t> widths(rows.front().size(), 0);
    for (const auto& row : rows) {
      for (std::size_t i = 0; i < row.size(); ++i) widths[i] = std::max(widths[i], row[i].size());
    }
    for (const auto& row : rows) {
      out << "  ";
      for (std::size_t i = 0; i < row.size(); ++i) {
        const bool numeric = i == 0 || i >= 5;  // id, messages, rate: right-aligned
        out << (numeric ? pad_left(row[i], widths[i]) : pad(row[i], widths[i])) << (i + 1 < row.size() ? "  " : "");
      }
      out << "\n";
    }
  }
  for (const std::string& p : r.problems) out << "problem:      " << p << "\n";
  return out.str();
}

}  // namespace robodds::mcap
