// impulse/world/collision_filter.hpp — which bodies may touch: each body's
// categories, the categories it collides with and its group; a world-wide
// predicate for what bits cannot say; and what a query sees.
#pragma once

#include <cstdint>

#include "../dynamics/fwd.hpp"

namespace impulse {

/// Every category bit set.
inline constexpr std::uint32_t all_categories = 0xffffffffu;

/// A body's collision filter (body_def::filter, world::set_filter).
///
/// Two bodies of the same nonzero group decide by the group alone: a
/// positive group always collides, a negative one never (the parts of one
/// ragdoll, say). Otherwise they collide when each one's mask has a bit of
/// the other's category. The defaults collide with everything.
struct collision_filter {
  std::uint32_t category = 1;           ///< the categories the body is in (bits)
  std::uint32_t mask = all_categories;  ///< the categories it collides with (bits)
  std::int32_t group = 0;               ///< 0: none
  friend constexpr bool operator==(const collision_filter&, const collision_filter&) = default;
};

/// Whether bodies of filters a and b may touch, as collision_filter says.
[[nodiscard]] constexpr bool should_collide(const collision_filter& a, const collision_filter& b) noexcept {
  if (a.group != 0 && a.group == b.group) return a.group > 0;
  return (a.mask & b.category) != 0 && (b.mask & a.category) != 0;
}

/// A user's rule for the pairs the bits let through (world::set_pair_filter):
/// test(a, b, context) returns false to keep the two apart. It is asked
/// when a pair's boxes begin to overlap (and may be asked again while they
/// do), and by continuous collision, from the task system's workers at
/// once: it must only read, and give the same answer for a pair until
/// world::refilter says otherwise. No test: every pair the bits let through.
struct pair_filter {
  bool (*test)(body_id a, body_id b, void* context) = nullptr;
  void* context = nullptr;
};

/// What a world query (ray_cast, overlap) sees: the bodies with a
/// category bit in mask, less those of a nonzero skip_group (a character's
/// own parts, say), and sensors only if asked. The defaults see every body
/// but the sensors.
struct query_filter {
  std::uint32_t mask = all_categories;
  std::int32_t skip_group = 0;
  bool sensors = false;
  [[nodiscard]] constexpr bool sees(const collision_filter& body, bool sensor) const noexcept {
    return (body.category & mask) != 0 && (skip_group == 0 || body.group != skip_group) && (sensors || !sensor);
  }
};

}  // namespace impulse
