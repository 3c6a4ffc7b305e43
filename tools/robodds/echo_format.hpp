#pragma once
// What `robodds echo` prints, from a sample already turned into named values (echo_sample.hpp):
// "name: value" text, one JSON object per sample, CSV rows; --field selection and --robot/--key
// filters. Pure (std only): no IDL type appears here.

#include <string>
#include <utility>
#include <vector>

namespace robodds {

/// One field's value as echo shows it.
struct EchoValue {
  enum class Kind { number, boolean, text, list, record };
  Kind kind = Kind::number;
  std::string text;               // number: shortest round-trip text ("0.5", "nan"); boolean: "true"/"false"; text: the string or enum name
  bool finite = true;             // number: false for NaN/Inf (JSON null)
  std::vector<EchoValue> items;   // list: the elements of a sequence
  std::vector<std::pair<std::string, EchoValue>> fields;  // record: a struct element of a sequence, fields in IDL order
};

/// A sample: its leaf fields in IDL order, nested structs as dotted names ("header.stamp_ns"),
/// fixed arrays as name[i].
using EchoFields = std::vector<std::pair<std::string, EchoValue>>;

/// One line's text of a value: a number or boolean as its text, a string or enum name bare, a
/// list as "[a, b]", a record as "{x: 60, y: 20}".
std::string echo_inline(const EchoValue& value);

/// "--- TITLE\n" then "  name: value\n" per field (what echo prints by default).
std::string echo_text(const std::string& title, const EchoFields& fields);

/// The sample as one JSON object on one line (no newline): dotted names nested as objects, name[i]
/// fields gathered into arrays, lists as arrays, records as objects, NaN/Inf as null, numbers exact.
std::string echo_json(const EchoFields& fields);

/// The CSV header (names, comma-separated) and one row (no newline): a list or record as its
/// echo_inline() text, quoted (RFC 4180) when it holds a comma, a quote or a line break.
std::string echo_csv_header(const EchoFields& fields);
std::string echo_csv_row(const EchoFields& fields);

/// The fields `paths` name, in the sample's order: a path names a field of that name or every
/// field under it ("header" names "header.stamp_ns", ...; "p" names "p[0]", "p[1]"). Every
/// path must name one: else std::invalid_argument "--field 'x': no such field; did you mean 'y'?
/// (fields: ...)".
EchoFields select_fields(const EchoFields& fields, const std::vector<std::string>& paths);

/// A "NAME=VALUE" filter (--key, --robot): the sample's field NAME reads VALUE (its echo_inline text).
struct EchoKeyFilter {
  std::string name;
  std::string value;
};
/// Parses "NAME=VALUE" (std::invalid_argument otherwise). `keys`: the type's key members; a NAME not
/// among them is refused with the closest ones.
EchoKeyFilter parse_key_filter(const std::string& text, const std::vector<std::string>& keys);
/// True when every filter's field reads its value.
bool matches(const EchoFields& fields, const std::vector<EchoKeyFilter>& filters);

}  // namespace robodds
