// impulse/narrowphase/detail/scratch_buffer.hpp — working space for one
// pair test, on the stack when it is small.
#pragma once

#include <cstddef>
#include <new>
#include <type_traits>
#include <vector>

namespace impulse::narrowphase::detail {

/// Room for `size` values: on the stack up to N (a collision hull's usual
/// size, so that a resting pair allocates nothing per step), on the heap
/// past that. The stack room is left uninitialised, so that asking for a
/// large N costs nothing until it is written: every value must be written
/// before it is read. U is a plain aggregate of numbers (vectors, planes,
/// contact points), whose objects an array of bytes provides as it is
/// written.
template <class U, std::size_t N>
class scratch_buffer {
  static_assert(std::is_trivially_copyable_v<U> && std::is_trivially_destructible_v<U>,
                "scratch_buffer holds plain values only");

 public:
  explicit scratch_buffer(std::size_t size) {
    if (size > N) large_.resize(size);
  }
  scratch_buffer(const scratch_buffer&) = delete;
  scratch_buffer& operator=(const scratch_buffer&) = delete;

  [[nodiscard]] U* data() noexcept {
    return large_.empty() ? std::launder(reinterpret_cast<U*>(small_)) : large_.data();
  }
  [[nodiscard]] const U* data() const noexcept {
    return large_.empty() ? std::launder(reinterpret_cast<const U*>(small_)) : large_.data();
  }
  U& operator[](std::size_t i) noexcept { return data()[i]; }

 private:
  alignas(U) unsigned char small_[N * sizeof(U)];
  std::vector<U> large_;
};

}  // namespace impulse::narrowphase::detail
