// bench/contact_memory/peers.hpp — what contact_memory.cpp and peers.cpp
// share: the allocation counters (defined in contact_memory.cpp, beside the
// operator new they count for) and Bullet's run, compiled in peers.cpp
// when the build found Bullet. peers.cpp is a target of its own, so that
// Bullet's headers and flags reach that file alone.
#pragma once

#include <cstddef>
#include <optional>

namespace contact_memory {

/// Bytes allocated and not yet freed, and their most since reset.
extern std::size_t held, peak;
/// Every allocation of the program goes through these two.
void* counted_alloc(std::size_t size, std::size_t align = alignof(std::max_align_t));
void counted_free(void* p) noexcept;

/// One run's bytes: before the step, the peak in it, after it; and the
/// pairs touching after it.
struct figures {
  std::size_t before, peak, after, touching;
};

/// The run on Bullet 3's btDiscreteDynamicsWorld; nothing without Bullet.
std::optional<figures> bullet_heap(int n);

}  // namespace contact_memory
