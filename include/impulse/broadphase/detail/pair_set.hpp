// impulse/broadphase/detail/pair_set.hpp — a set of pairs of 32-bit handles
// that an incremental broad phase adds to and removes from as boxes move.
//
// Open addressing with linear probing over one power-of-two array of 64-bit
// keys (the two handles, lower first), and deletion by backward shift
// (Knuth, TAOCP vol. 3, §6.4, algorithm R), so that no tombstones pile up
// in a set that sees a remove for every add over a long run. Kept below half
// full, where linear probing averages under 1.5 probes for a hit and 2.5 for
// a miss. std::unordered_set would allocate a node per pair and costs far
// more to include.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace impulse::broadphase::detail {

class pair_set {
 public:
  static constexpr std::uint64_t key_of(std::uint32_t x, std::uint32_t y) noexcept {
    return x < y ? (std::uint64_t(x) << 32) | y : (std::uint64_t(y) << 32) | x;
  }
  static constexpr std::uint32_t first(std::uint64_t key) noexcept { return std::uint32_t(key >> 32); }
  static constexpr std::uint32_t second(std::uint64_t key) noexcept { return std::uint32_t(key); }

  /// Adds the key; false when it was already there.
  bool insert(std::uint64_t key) {
    if (2 * (size_ + 1) > keys_.size()) grow();
    std::size_t i = home(key);
    while (keys_[i] != empty) {
      if (keys_[i] == key) return false;
      i = (i + 1) & mask_;
    }
    keys_[i] = key;
    ++size_;
    return true;
  }

  /// Removes the key; false when it was not there.
  bool erase(std::uint64_t key) noexcept {
    if (size_ == 0) return false;
    std::size_t i = home(key);
    while (keys_[i] != key) {
      if (keys_[i] == empty) return false;
      i = (i + 1) & mask_;
    }
    // Backward shift: pull later keys of the same probe run into the hole
    // when the hole lies on their way from their home slot.
    for (std::size_t j = (i + 1) & mask_;; j = (j + 1) & mask_) {
      if (keys_[j] == empty) break;
      const std::size_t h = home(keys_[j]);
      const bool hole_between = i <= j ? (h <= i || h > j) : (h <= i && h > j);
      if (hole_between) {
        keys_[i] = keys_[j];
        i = j;
      }
    }
    keys_[i] = empty;
    --size_;
    return true;
  }

  void clear() noexcept {
    for (std::uint64_t& k : keys_) k = empty;
    size_ = 0;
  }

  /// Calls f(key) for every key, in table order.
  template <class F>
  void for_each(F&& f) const {
    for (const std::uint64_t k : keys_)
      if (k != empty) f(k);
  }

  /// Removes every key for which drop(key) is true (one pass and a rehash).
  template <class Predicate>
  void erase_if(Predicate&& drop) {
    scratch_.clear();
    for (const std::uint64_t k : keys_)
      if (k != empty && !drop(k)) scratch_.push_back(k);
    clear();
    for (const std::uint64_t k : scratch_) insert(k);
  }

  [[nodiscard]] std::size_t size() const noexcept { return size_; }

 private:
  // No real key is all ones: handles are below 2^32 - 1.
  static constexpr std::uint64_t empty = ~std::uint64_t(0);

  std::size_t home(std::uint64_t key) const noexcept {
    // The splitmix64 finaliser: handles are small consecutive integers,
    // which a plain mask would pile into a few runs.
    key ^= key >> 30;
    key *= 0xbf58476d1ce4e5b9ull;
    key ^= key >> 27;
    key *= 0x94d049bb133111ebull;
    key ^= key >> 31;
    return std::size_t(key) & mask_;
  }

  void grow() {
    std::vector<std::uint64_t> old;
    old.swap(keys_);
    keys_.assign(old.empty() ? 64 : old.size() * 2, empty);
    mask_ = keys_.size() - 1;
    size_ = 0;
    for (const std::uint64_t k : old)
      if (k != empty) insert(k);
  }

  std::vector<std::uint64_t> keys_;
  std::vector<std::uint64_t> scratch_;
  std::size_t mask_ = 0;
  std::size_t size_ = 0;
};

}  // namespace impulse::broadphase::detail
