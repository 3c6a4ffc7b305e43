#include "common/json_writer.hpp"

#include <cmath>
#include <cstdio>

namespace robodds {

std::string json_number(double v) {
  if (!std::isfinite(v)) {
    return "null";
  }
  char buf[40];
  std::snprintf(buf, sizeof(buf), "%.12g", v);
  return buf;
}

std::string json_escape(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof(buf), "\\u%04x", c);
          out += buf;
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

void JsonWriter::key_prefix(const std::string& key) {
  if (!first_.empty()) {
    if (!first_.back()) {
      out_ += ",";
    }
    first_.back() = false;
    out_ += "\n" + std::string(static_cast<std::size_t>(depth_) * 2, ' ');
  }
  if (!key.empty()) {
    out_ += json_escape(key) + ": ";
  }
}

JsonWriter& JsonWriter::begin_object(const std::string& key) {
  key_prefix(key);
  out_ += "{";
  first_.push_back(true);
  ++depth_;
  return *this;
}

JsonWriter& JsonWriter::end_object() {
  --depth_;
  const bool empty = first_.back();
  first_.pop_back();
  out_ += empty ? "}" : "\n" + std::string(static_cast<std::size_t>(depth_) * 2, ' ') + "}";
  if (first_.empty()) {
    out_ += "\n";
  }
  return *this;
}

JsonWriter& JsonWriter::begin_array(const std::string& key) {
  key_prefix(key);
  out_ += "[";
  first_.push_back(true);
  ++depth_;
  return *this;
}

JsonWriter& JsonWriter::end_array() {
  --depth_;
  const bool empty = first_.back();
  first_.pop_back();
  out_ += empty ? "]" : "\n" + std::string(static_cast<std::size_t>(depth_) * 2, ' ') + "]";
  return *this;
}

JsonWriter& JsonWriter::value(const std::string& key, double v) {
  key_prefix(key);
  out_ += json_number(v);
  return *this;
}

JsonWriter& JsonWriter::value(const std::string& key, std::int64_t v) {
  key_prefix(key);
  out_ += std::to_string(v);
  return *this;
}

JsonWriter& JsonWriter::value(const std::string& key, bool v) {
  key_prefix(key);
  out_ += v ? "true" : "false";
  return *this;
}

JsonWriter& JsonWriter::value(const std::string& key, const std::string& v) {
  key_prefix(key);
  out_ += json_escape(v);
  return *this;
}

JsonWriter& JsonWriter::value(const std::string& key, const std::vector<double>& v) {
  key_prefix(key);
  out_ += "[";
  for (std::size_t i = 0; i < v.size(); ++i) {
    out_ += (i == 0 ? "" : ", ") + json_number(v[i]);
  }
  out_ += "]";
  return *this;
}

}  // namespace robodds
