#pragma once
// A line diff for tests and tools that compare a checked-in generated file with what its
// generator renders now (docs/topics.md's table, config/*.params.yaml). Pure: std only.

#include <string>

namespace robodds {

/// The lines only in `from` as "- line" and the lines only in `to` as "+ line", in order (a
/// longest-common-subsequence diff; meant for files of a few hundred lines). "" when equal line
/// by line.
std::string line_diff(const std::string& from, const std::string& to);

}  // namespace robodds
