// impulse/dynamics/detail/island.hpp — islands: the groups of bodies that touch,
// directly or through others, and so must wake and sleep together.
//
// Union–find with path halving and union by size (Tarjan 1975): rebuilding
// the islands from the touching contacts every step costs a near-constant
// time per contact, which is less than keeping them incrementally (Box2D
// v3 links islands as contacts begin and splits them lazily when one
// sleeps) and cannot go stale. Static bodies join no island: a floor
// would otherwise make one island of everything on it.
#pragma once

#include <cstdint>
#include <numeric>
#include <utility>
#include <vector>

namespace impulse::detail {

class union_find {
 public:
  void reset(std::size_t n) {
    parent_.resize(n);
    size_.assign(n, 1);
    std::iota(parent_.begin(), parent_.end(), std::uint32_t{0});
  }
  [[nodiscard]] std::uint32_t find(std::uint32_t i) noexcept {
    while (parent_[i] != i) {
      parent_[i] = parent_[parent_[i]];
      i = parent_[i];
    }
    return i;
  }
  void unite(std::uint32_t a, std::uint32_t b) noexcept {
    a = find(a), b = find(b);
    if (a == b) return;
    if (size_[a] < size_[b]) std::swap(a, b);
    parent_[b] = a;
    size_[a] += size_[b];
  }

 private:
  std::vector<std::uint32_t> parent_, size_;
};

}  // namespace impulse::detail
