// bench/broadphase/peers.hpp — the peers' broad phases (Bullet's, when the
// build found it) behind the calls the benchmark makes. peers.cpp is a
// target of its own, so that Bullet's headers and flags reach that file
// alone and broadphase.cpp compiles to the same object with or without it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "moving_boxes.hpp"

namespace bench {

/// A broad phase as the benchmark drives it.
class broad_phase_driver {
 public:
  virtual ~broad_phase_driver() = default;
  virtual void create(const box& b) = 0;
  virtual void move(std::uint32_t i, const box& b) = 0;
  virtual void update() = 0;
  [[nodiscard]] virtual std::size_t pair_count() const = 0;
};

/// A peer's broad phase: its name in the table, the largest N it runs at,
/// and how to make one for boxes within `bounds`, `capacity` of them.
struct peer_broad_phase {
  const char* name;
  int max_n;
  std::function<std::unique_ptr<broad_phase_driver>(const box& bounds, std::size_t capacity)> make;
};

/// The peers this build has (none without Bullet).
std::vector<peer_broad_phase> peer_broad_phases();

}  // namespace bench
