#pragma once
// Files that a reader (or a later process) must see whole or not at all, such as summary.json,
// which the evaluator writes and the runner may rewrite after a failed run.

#include <string>

namespace robodds {

/// Writes `text` to `path` through `path`.tmp renamed over `path`: a process that dies meanwhile
/// leaves the old file or none, never half of the new one. Returns an empty string on success,
/// else one line naming the file and the reason ("cannot write P.tmp: ...", "cannot rename ...").
std::string replace_file(const std::string& path, const std::string& text);

}  // namespace robodds
