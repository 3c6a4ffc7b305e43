#include "common/did_you_mean.hpp"

#include <algorithm>
#include <cctype>
#include <limits>

namespace robodds {
namespace {

char lower(char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); }

bool starts_with_ignoring_case(std::string_view text, std::string_view prefix) {
  if (prefix.size() > text.size()) {
    return false;
  }
  for (std::size_t i = 0; i < prefix.size(); ++i) {
    if (lower(text[i]) != lower(prefix[i])) {
      return false;
    }
  }
  return true;
}

/// `known` whole, then its tails after each '.' or '/'.
std::vector<std::string_view> forms_of(std::string_view known) {
  std::vector<std::string_view> forms{known};
  for (std::size_t i = 0; i < known.size(); ++i) {
    if ((known[i] == '.' || known[i] == '/') && i + 1 < known.size()) {
      forms.push_back(known.substr(i + 1));
    }
  }
  return forms;
}

}  // namespace

std::size_t edit_distance(std::string_view a, std::string_view b) {
  // Three rows of the dynamic programme: the transposition looks two rows back.
  std::vector<std::size_t> before(b.size() + 1), previous(b.size() + 1), current(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) {
    previous[j] = j;
  }
  for (std::size_t i = 1; i <= a.size(); ++i) {
    current[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t substitution = lower(a[i - 1]) == lower(b[j - 1]) ? 0 : 1;
      current[j] = std::min({previous[j] + 1, current[j - 1] + 1, previous[j - 1] + substitution});
      if (i > 1 && j > 1 && lower(a[i - 1]) == lower(b[j - 2]) && lower(a[i - 2]) == lower(b[j - 1])) {
        current[j] = std::min(current[j], before[j - 2] + 1);
      }
    }
    before.swap(previous);
    previous.swap(current);
  }
  return previous[b.size()];
}

std::vector<std::string> closest_names(std::string_view name, const std::vector<std::string>& known,
                                       std::size_t max_names) {
  if (name.empty() || std::find(known.begin(), known.end(), name) != known.end()) {
    return {};
  }
  const std::size_t allowed = std::max<std::size_t>(1, name.size() / 3);
  struct Candidate {
    std::size_t score;  // edits; a prefix match scores as one edit past the allowed typos
    std::size_t order;  // position in `known`: ties keep the caller's order
    const std::string* name;
  };
  std::vector<Candidate> candidates;
  for (std::size_t k = 0; k < known.size(); ++k) {
    std::size_t best = std::numeric_limits<std::size_t>::max();
    for (std::string_view form : forms_of(known[k])) {
      const std::size_t distance = edit_distance(name, form);
      if (distance <= allowed && distance < name.size()) {  // "c" is not a typo of "a"
        best = std::min(best, distance);
      } else if (name.size() >= 3 && starts_with_ignoring_case(form, name)) {
        best = std::min(best, allowed + 1);
      }
    }
    if (best != std::numeric_limits<std::size_t>::max()) {
      candidates.push_back({best, k, &known[k]});
    }
  }
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& x, const Candidate& y) {
    return x.score != y.score ? x.score < y.score : x.order < y.order;
  });
  std::vector<std::string> out;
  for (const Candidate& c : candidates) {
    if (out.size() == max_names) {
      break;
    }
    if (std::find(out.begin(), out.end(), *c.name) == out.end()) {
      out.push_back(*c.name);
    }
  }
  return out;
}

std::vector<std::string> listed_names(std::string_view list) {
  std::vector<std::string> names;
  std::size_t start = 0;
  while (start <= list.size()) {
    std::size_t end = list.find(',', start);
    end = end == std::string_view::npos ? list.size() : end;
    std::string_view name = list.substr(start, end - start);
    while (!name.empty() && name.front() == ' ') name.remove_prefix(1);
    while (!name.empty() && name.back() == ' ') name.remove_suffix(1);
    if (!name.empty()) {
      names.emplace_back(name);
    }
    start = end + 1;
  }
  return names;
}

std::string did_you_mean(std::string_view name, const std::vector<std::string>& known) {
  const std::vector<std::string> names = closest_names(name, known);
  if (names.empty()) {
    return "";
  }
  std::string out = "; did you mean ";
  for (std::size_t i = 0; i < names.size(); ++i) {
    out += i == 0 ? "" : (i + 1 == names.size() ? " or " : ", ");
    out += "'" + names[i] + "'";
  }
  return out + "?";
}

}  // namespace robodds
