#include "tools/cli/one_of.hpp"

#include <algorithm>

#include "common/did_you_mean.hpp"

namespace robodds::cli {

CLI::Validator one_of(std::vector<std::string> words) {
  std::string set = "{";
  for (const std::string& word : words) {
    set += (set.size() == 1 ? "" : ",") + word;
  }
  set += "}";
  return CLI::Validator(
      [words, set](std::string& value) -> std::string {
        if (std::find(words.begin(), words.end(), value) != words.end()) {
          return "";
        }
        return value + " not in " + set + did_you_mean(value, words);
      },
      set);
}

}  // namespace robodds::cli
