// impulse/broadphase/fwd.hpp — the broad phase module's names.
#pragma once

#include "../core/policy.hpp"
#include "../core/slot_map.hpp"

namespace impulse {

struct proxy_tag;
/// Names a proxy (a box and its user data) in a broad phase.
using proxy_id = object_id<proxy_tag>;
struct proxy_pair;
template <scalar_type T> struct ray;

namespace broadphase {
template <scalar_type T> class basic_brute_force;
struct brute_force;
}  // namespace broadphase

}  // namespace impulse
