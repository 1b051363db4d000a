// impulse/broadphase/fwd.hpp — the broad phase module's names.
#pragma once

#include "../core/policy.hpp"
#include "../core/slot_map.hpp"

namespace impulse {

/// Proxies never leave their broad phase: their ids name no owner.
struct proxy_tag {
  static constexpr bool owned = false;
};
/// Names a proxy (a box and its user data) in a broad phase.
using proxy_id = object_id<proxy_tag>;
static_assert(sizeof(proxy_id) == 8, "a proxy id carries no owner: it never leaves its broad phase");
struct proxy_pair;

namespace broadphase {
template <scalar_type T> class basic_brute_force;
template <scalar_type T> class basic_sweep_and_prune;
template <scalar_type T> class basic_spatial_hash;
template <scalar_type T> class basic_dynamic_bvh;
template <scalar_type T> class basic_octree;
struct brute_force;
struct sweep_and_prune;
struct spatial_hash;
struct dynamic_bvh;
struct octree;
}  // namespace broadphase

}  // namespace impulse
