// impulse/dynamics/fwd.hpp — the dynamics module's names.
#pragma once

#include <cstdint>

#include "../core/policy.hpp"

namespace impulse {

enum class body_type : std::uint8_t;
template <scalar_type T> struct rigid_body;

}  // namespace impulse
