#pragma once
// Dense numbers for 64-bit keys (topic instance keys, robot ids): the first key inserted is 0,
// the next new one 1, ... find() and insert() cost O(1) whatever the number of keys: an
// open-addressing table in one array (Fibonacci hashing, linear probing, at most half full).
// Inputs look up each sample's instance with it: per sample an ordered map cost log N lookups,
// each a cache miss, and made the cost per robot-tick grow with the robots (docs/performance.md,
// "Cost per robot-tick"). Not thread-safe; keys cannot be removed.

#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace robodds {

class KeyIndex {
 public:
  static constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();

  /// The key's number, or kNone if it was never inserted.
  std::size_t find(std::uint64_t key) const {
    if (table_.empty()) {
      return kNone;
    }
    for (std::size_t i = home(key);; i = (i + 1) & mask()) {
      const Entry& e = table_[i];
      if (e.number == 0) {
        return kNone;
      }
      if (e.key == key) {
        return e.number - 1;
      }
    }
  }

  /// The key's number and true if it is new (then its number is the former size()).
  std::pair<std::size_t, bool> insert(std::uint64_t key) {
    if ((size_ + 1) * 2 > table_.size()) {
      grow();
    }
    for (std::size_t i = home(key);; i = (i + 1) & mask()) {
      Entry& e = table_[i];
      if (e.number == 0) {
        e = Entry{key, ++size_};
        return {size_ - 1, true};
      }
      if (e.key == key) {
        return {e.number - 1, false};
      }
    }
  }

  std::size_t size() const { return size_; }

 private:
  struct Entry {
    std::uint64_t key = 0;
    std::size_t number = 0;  // the key's number + 1; 0: empty entry
  };

  std::size_t mask() const { return table_.size() - 1; }
  /// Fibonacci hashing: the top bits of key * 2^64/phi; consecutive keys land far apart.
  std::size_t home(std::uint64_t key) const {
    return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ULL) >> (64 - bits_));
  }
  void grow() {
    std::vector<Entry> old = std::move(table_);
    bits_ = old.empty() ? 4 : bits_ + 1;
    table_.assign(std::size_t{1} << bits_, Entry{});
    for (const Entry& e : old) {
      if (e.number != 0) {
        std::size_t i = home(e.key);
        while (table_[i].number != 0) {
          i = (i + 1) & mask();
        }
        table_[i] = e;
      }
    }
  }

  std::vector<Entry> table_;  // size 2^bits_ (or empty)
  unsigned bits_ = 0;
  std::size_t size_ = 0;
};

}  // namespace robodds
