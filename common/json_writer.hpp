#pragma once
// A small deterministic JSON writer (numbers with 12 significant digits, keys in call order).
// Enough for summary.json; no parsing.

#include <cstdint>
#include <string>
#include <vector>

namespace robodds {

class JsonWriter {
 public:
  JsonWriter& begin_object(const std::string& key = "");
  JsonWriter& end_object();
  JsonWriter& begin_array(const std::string& key = "");
  JsonWriter& end_array();
  JsonWriter& value(const std::string& key, double v);
  JsonWriter& value(const std::string& key, std::int64_t v);
  JsonWriter& value(const std::string& key, bool v);
  JsonWriter& value(const std::string& key, const std::string& v);
  JsonWriter& value(const std::string& key, const char* v) { return value(key, std::string(v)); }
  JsonWriter& value(const std::string& key, const std::vector<double>& v);
  const std::string& str() const { return out_; }

 private:
  void key_prefix(const std::string& key);
  std::string out_;
  std::vector<bool> first_;  // per open container: no element written yet
  int depth_ = 0;
};

/// JSON text of a double (null for NaN/Inf).
std::string json_number(double v);
std::string json_escape(const std::string& text);

}  // namespace robodds
