// The pair tracker: one update's pairs sorted as operator< sorts them (by a
// radix sort past 256 pairs), and what began and ended since the last one.
#include <doctest/doctest.h>

#include <algorithm>
#include <cstdint>
#include <vector>

#include "impulse/broadphase/detail/pair_tracker.hpp"
#include "impulse/core/random.hpp"

namespace broadphase_pair_tracker_tests {

using namespace impulse;

TEST_CASE("the pair tracker sorts like operator< and finds what began and ended") {
  // Slots up to 2^20 (two passes of the radix sort per slot), some lists
  // below the 256 where std::sort takes over.
  lcg32 random{7};
  broadphase::detail::pair_tracker tracker;
  std::vector<proxy_pair> previous;
  for (const std::size_t count : {std::size_t(100), std::size_t(5000), std::size_t(300), std::size_t(20000)}) {
    std::vector<proxy_pair> found;
    for (std::size_t i = 0; i < count; ++i) {
      const std::uint32_t a = random.next() % (1u << 20), b = random.next() % (1u << 20);
      if (a != b) found.push_back(pair_of({a, a % 3}, {b, b % 5}));
    }
    // Half of the previous update's pairs carry on.
    for (std::size_t i = 0; i < previous.size(); i += 2) found.push_back(previous[i]);
    std::sort(found.begin(), found.end());
    found.erase(std::unique(found.begin(), found.end()), found.end());
    const std::vector<proxy_pair> expected = found;
    std::vector<proxy_pair> shuffled = found;
    for (std::size_t i = shuffled.size() - 1; i > 0; --i) std::swap(shuffled[i], shuffled[random.next() % (i + 1)]);

    tracker.publish(shuffled);
    CHECK(std::equal(tracker.pairs().begin(), tracker.pairs().end(), expected.begin(), expected.end()));
    std::vector<proxy_pair> begun, ended;
    std::set_difference(expected.begin(), expected.end(), previous.begin(), previous.end(), std::back_inserter(begun));
    std::set_difference(previous.begin(), previous.end(), expected.begin(), expected.end(), std::back_inserter(ended));
    CHECK(std::equal(tracker.begun().begin(), tracker.begun().end(), begun.begin(), begun.end()));
    CHECK(std::equal(tracker.ended().begin(), tracker.ended().end(), ended.begin(), ended.end()));
    CHECK(ended.size() + 1 >= previous.size() / 2);  // the other half ended
    previous = expected;
  }
}

}  // namespace broadphase_pair_tracker_tests
