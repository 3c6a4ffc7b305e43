#pragma once
// Near misses of a name the user typed: the known names closest to it by edit distance, so that
// every "unknown component/parameter/topic/key/subcommand" error can say "did you mean 'x'?".

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace robodds {

/// Levenshtein distance with adjacent transpositions counted as one edit ("optimal string
/// alignment"), case-insensitive (ASCII): "stat" -> "state" is 1, "recrod" -> "record" is 1.
std::size_t edit_distance(std::string_view a, std::string_view b);

/// The known names close to `name`, best first, at most `max_names`. A known name is compared
/// whole and by each tail after a '.' or '/' ("controller.epsilon_m" also as "epsilon_m",
/// "plant/state" as "state"), so a name typed without its prefix finds the prefixed one. Close
/// means at most max(1, length / 3) edits and fewer than its length (a typo, not a different
/// word: "c" is no typo of "a"), or that `name` (of 3
/// characters or more) starts a known name or one of its tails ("epsilon" -> "epsilon_m").
/// Empty when nothing is close, or when `name` itself is known.
std::vector<std::string> closest_names(std::string_view name, const std::vector<std::string>& known,
                                       std::size_t max_names = 3);

/// The names of a comma-separated list ("id, x, y": {"id", "x", "y"}), for messages that
/// already spell their known names as one text.
std::vector<std::string> listed_names(std::string_view list);

/// "; did you mean 'x'?" ("'x' or 'y'", "'x', 'y' or 'z'") for closest_names(name, known), or ""
/// when nothing is close: appended right after the unknown name in an error message, the one
/// form every such message uses.
std::string did_you_mean(std::string_view name, const std::vector<std::string>& known);

}  // namespace robodds
