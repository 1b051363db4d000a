// impulse/broadphase/pair_tracker.hpp — the overlapping pairs after an
// update, and what changed since the one before.
//
// Every broad phase reports the whole current set of pairs, sorted, plus
// the pairs that began and ended since the previous update. The whole set
// because the narrow phase needs every touching pair every step anyway; the
// differences because contact begin and end events need them, and every
// broad phase can afford them this way: a sort and one merge over sets the
// step already touches. (An incremental sweep and prune knows the
// differences first-hand; it still reports through here, so that all broad
// phases agree by construction on what a "began" pair is.) A destroyed
// proxy's pairs are reported as ended at the next update; pairs compare
// with their ids' generations, so a new proxy in a freed slot starts new
// pairs rather than continuing the old proxy's.
#pragma once

#include <algorithm>
#include <cstddef>
#include <span>
#include <vector>

#include "proxy.hpp"

namespace impulse::broadphase::detail {

class pair_tracker {
 public:
  /// Takes this update's pairs (any order, each once) and works out what
  /// began and ended against the previous update's.
  void publish(std::vector<proxy_pair>& found) {
    std::sort(found.begin(), found.end());
    begun_.clear();
    ended_.clear();
    std::size_t i = 0, j = 0;
    while (i < current_.size() || j < found.size()) {
      if (j == found.size() || (i < current_.size() && current_[i] < found[j])) {
        ended_.push_back(current_[i++]);
      } else if (i == current_.size() || found[j] < current_[i]) {
        begun_.push_back(found[j++]);
      } else {
        ++i, ++j;
      }
    }
    current_.swap(found);
  }

  [[nodiscard]] std::span<const proxy_pair> pairs() const noexcept { return current_; }
  [[nodiscard]] std::span<const proxy_pair> begun() const noexcept { return begun_; }
  [[nodiscard]] std::span<const proxy_pair> ended() const noexcept { return ended_; }

 private:
  std::vector<proxy_pair> current_, begun_, ended_;
};

}  // namespace impulse::broadphase::detail
