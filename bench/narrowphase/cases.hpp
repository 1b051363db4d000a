// bench/narrowphase/cases.hpp — a line of the table, shared by
// narrowphase.cpp (ours) and peers.cpp (libccd's and Bullet's): a pass over
// the pairs, its times, and its error against the exact answers.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "convex_pairs.hpp"

namespace narrowphase_bench {

/// Where an engine gives no figure.
inline constexpr double not_given = std::numeric_limits<double>::quiet_NaN();

/// One line of the table: a pass over the pairs that returns a checksum
/// (so that the compiler keeps the work), the times of the passes, and the
/// error measured on a separate, untimed pass.
struct timed_case {
  std::string pair, algorithm, engine;
  std::size_t tests = 0;
  std::function<double()> pass;
  double max_error = not_given;
  std::vector<double> ns_per_test;

  [[nodiscard]] double median() const {
    std::vector<double> v = ns_per_test;
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
  }
};

/// A case from `signed_distance(i)`: the engine's signed distance for pair
/// i, or NaN where it gives none. `reference[i]` is the exact one; for a
/// collide test (`overlap_only`) a pair it finds apart is skipped when
/// they are apart and counts its whole depth when they overlap.
template <class F>
timed_case make_case(std::string pair, std::string algorithm, std::string engine, const std::vector<std::size_t>& which,
                     const std::vector<double>& reference, F signed_distance, bool measured = true) {
  timed_case c{std::move(pair), std::move(algorithm), std::move(engine), which.size(), {}, not_given, {}};
  for (const std::size_t i : which) {
    if (!measured) break;
    const double s = signed_distance(i);
    if (std::isnan(s)) continue;
    const double e = std::abs(s - reference[i]);
    c.max_error = std::isnan(c.max_error) ? e : std::max(c.max_error, e);
  }
  c.pass = [which, signed_distance]() {
    double sum = 0;
    for (const std::size_t i : which) sum += signed_distance(i);
    return sum;
  };
  return c;
}

/// The peers' cases of a pairing, those compiled in (peers.cpp): libccd's
/// GJK/EPA and MPR, Bullet's GJK/EPA and, for two boxes, its
/// btBoxBoxDetector. peers.cpp is a target of its own, so that the peers'
/// headers and flags reach it alone.
void add_peers(std::vector<timed_case>& cases, const std::string& pair, const peers::generated_pairs& g,
               const std::vector<std::size_t>& all, const std::vector<double>& reference,
               const std::vector<std::size_t>& separated, bool distance_row, bool boxes);

}  // namespace narrowphase_bench
