#pragma once
// The output directory of a run (--out), checked before the first tick so that a run never
// ends with its results lost.

#include <string>

namespace robodds {

/// Makes sure `dir` is a directory this process can write to, before anything runs: creates it
/// and its parents, then writes and removes a probe file. ConfigError naming `dir` and the reason
/// (a file of that name, a parent that is a file, cannot be created, not writable) otherwise.
/// `robodds run`, and `robodds host` / component executables given --out, call it.
void make_output_dir(const std::string& dir);

}  // namespace robodds
