#include "tools/robodds/echo_format.hpp"

#include <stdexcept>

#include "common/did_you_mean.hpp"
#include "common/json_writer.hpp"

namespace robodds {
namespace {

std::vector<std::string> names_of(const EchoFields& fields) {
  std::vector<std::string> names;
  for (const auto& [name, value] : fields) {
    names.push_back(name);
  }
  return names;
}

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& name : names) {
    out += (out.empty() ? "" : ", ") + name;
  }
  return out;
}

void append_json(std::string& out, const EchoValue& value);

void append_json_fields(std::string& out, const std::vector<std::pair<std::string, EchoValue>>& fields) {
  out += '{';
  for (std::size_t i = 0; i < fields.size(); ++i) {
    out += (i == 0 ? "" : ",") + json_escape(fields[i].first) + ":";
    append_json(out, fields[i].second);
  }
  out += '}';
}

void append_json(std::string& out, const EchoValue& value) {
  switch (value.kind) {
    case EchoValue::Kind::number:
      out += value.finite ? value.text : "null";  // JSON has no NaN or Inf
      break;
    case EchoValue::Kind::boolean:
      out += value.text;
      break;
    case EchoValue::Kind::text:
      out += json_escape(value.text);
      break;
    case EchoValue::Kind::list:
      out += '[';
      for (std::size_t i = 0; i < value.items.size(); ++i) {
        out += i == 0 ? "" : ",";
        append_json(out, value.items[i]);
      }
      out += ']';
      break;
    case EchoValue::Kind::record:
      append_json_fields(out, value.fields);
      break;
  }
}

/// The JSON shape of a sample: dotted names become nested objects, name[i] an array's elements.
struct JsonNode {
  const EchoValue* leaf = nullptr;
  bool is_array = false;
  std::vector<std::pair<std::string, JsonNode>> children;  // object members, or array elements (empty keys)
};

JsonNode& child(JsonNode& node, const std::string& key) {
  for (auto& [name, sub] : node.children) {
    if (name == key) {
      return sub;
    }
  }
  node.children.emplace_back(key, JsonNode{});
  return node.children.back().second;
}

void insert(JsonNode& root, const std::string& path, const EchoValue& value) {
  JsonNode* node = &root;
  std::size_t start = 0;
  while (true) {
    const std::size_t dot = path.find('.', start);
    std::string segment = path.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    // "name[3]": member "name", an array, its element "3" (elements come in index order).
    const std::size_t bracket = segment.find('[');
    if (bracket != std::string::npos && segment.back() == ']') {
      node = &child(*node, segment.substr(0, bracket));
      node->is_array = true;
      segment = segment.substr(bracket + 1, segment.size() - bracket - 2);
    }
    node = &child(*node, segment);
    if (dot == std::string::npos) {
      node->leaf = &value;
      return;
    }
    start = dot + 1;
  }
}

void append_node(std::string& out, const JsonNode& node) {
  if (node.leaf != nullptr) {
    append_json(out, *node.leaf);
    return;
  }
  out += node.is_array ? '[' : '{';
  for (std::size_t i = 0; i < node.children.size(); ++i) {
    out += i == 0 ? "" : ",";
    if (!node.is_array) {
      out += json_escape(node.children[i].first) + ":";
    }
    append_node(out, node.children[i].second);
  }
  out += node.is_array ? ']' : '}';
}

std::string csv_cell(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) {
    return text;
  }
  std::string out = "\"";
  for (char c : text) {
    out += c == '"' ? "\"\"" : std::string(1, c);
  }
  return out + "\"";
}

bool under(const std::string& name, const std::string& path) {
  return name == path || (name.size() > path.size() && name.compare(0, path.size(), path) == 0 &&
                          (name[path.size()] == '.' || name[path.size()] == '['));
}

}  // namespace

std::string echo_inline(const EchoValue& value) {
  switch (value.kind) {
    case EchoValue::Kind::list: {
      std::string out = "[";
      for (std::size_t i = 0; i < value.items.size(); ++i) {
        out += (i == 0 ? "" : ", ") + echo_inline(value.items[i]);
      }
      return out + "]";
    }
    case EchoValue::Kind::record: {
      std::string out = "{";
      for (std::size_t i = 0; i < value.fields.size(); ++i) {
        out += (i == 0 ? "" : ", ") + value.fields[i].first + ": " + echo_inline(value.fields[i].second);
      }
      return out + "}";
    }
    default:
      return value.text;
  }
}

std::string echo_text(const std::string& title, const EchoFields& fields) {
  std::string out = "--- " + title + "\n";
  for (const auto& [name, value] : fields) {
    out += "  " + name + ": " + echo_inline(value) + "\n";
  }
  return out;
}

std::string echo_json(const EchoFields& fields) {
  JsonNode root;
  for (const auto& [name, value] : fields) {
    insert(root, name, value);
  }
  std::string out;
  append_node(out, root);
  return out == "" ? "{}" : out;
}

std::string echo_csv_header(const EchoFields& fields) {
  std::string out;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    out += (i == 0 ? "" : ",") + csv_cell(fields[i].first);
  }
  return out;
}

std::string echo_csv_row(const EchoFields& fields) {
  std::string out;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    out += (i == 0 ? "" : ",") + csv_cell(echo_inline(fields[i].second));
  }
  return out;
}

EchoFields select_fields(const EchoFields& fields, const std::vector<std::string>& paths) {
  for (const std::string& path : paths) {
    bool found = false;
    for (const auto& [name, value] : fields) {
      found = found || under(name, path);
    }
    if (!found) {
      const std::vector<std::string> names = names_of(fields);
      throw std::invalid_argument("--field '" + path + "': no such field" + did_you_mean(path, names) + " (fields: " +
                                  joined(names) + ")");
    }
  }
  EchoFields chosen;
  for (const auto& field : fields) {
    for (const std::string& path : paths) {
      if (under(field.first, path)) {
        chosen.push_back(field);
        break;
      }
    }
  }
  return chosen;
}

EchoKeyFilter parse_key_filter(const std::string& text, const std::vector<std::string>& keys) {
  const std::size_t equals = text.find('=');
  if (equals == std::string::npos || equals == 0 || equals + 1 == text.size()) {
    throw std::invalid_argument("--key '" + text + "': expected NAME=VALUE (e.g. robot_id=1; keys: " + joined(keys) + ")");
  }
  EchoKeyFilter filter{text.substr(0, equals), text.substr(equals + 1)};
  bool known = false;
  for (const std::string& key : keys) {
    known = known || key == filter.name;
  }
  if (!known) {
    throw std::invalid_argument("--key '" + text + "': '" + filter.name + "' is no key of the topic" +
                                did_you_mean(filter.name, keys) + " (keys: " + (keys.empty() ? "none" : joined(keys)) + ")");
  }
  return filter;
}

bool matches(const EchoFields& fields, const std::vector<EchoKeyFilter>& filters) {
  for (const EchoKeyFilter& filter : filters) {
    bool ok = false;
    for (const auto& [name, value] : fields) {
      ok = ok || (name == filter.name && echo_inline(value) == filter.value);
    }
    if (!ok) {
      return false;
    }
  }
  return true;
}

}  // namespace robodds
