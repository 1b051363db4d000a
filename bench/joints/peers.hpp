// bench/joints/peers.hpp — the two scenes on Bullet (libbullet-dev), when
// the build found it. peers.cpp is a target of its own (CMakeLists.txt), so
// that Bullet's headers and flags reach that file alone and main.cpp
// compiles to the same object with or without Bullet.
#pragma once

#include <optional>

#include "measure.hpp"
#include "ragdoll_pile.hpp"

namespace joints_bench {

/// Whether this build has Bullet.
bool have_bullet() noexcept;

/// The joint grid on Bullet; nothing without it.
std::optional<result> run_bullet(const grid_spec& spec);
/// The ragdoll pile on Bullet; nothing without it.
std::optional<result> run_bullet(const ragdoll_pile_spec& spec);

}  // namespace joints_bench
