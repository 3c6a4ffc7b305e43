#pragma once
// A CLI11 check that an option's value is one of a few words, like CLI::IsMember, whose message
// it keeps ("--deploy: proceses not in {colocated,processes}"), naming the closest word too
// ("; did you mean 'processes'?").

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace robodds::cli {

/// The validator: `->check(one_of({"colocated", "processes"}))`.
CLI::Validator one_of(std::vector<std::string> words);

}  // namespace robodds::cli
