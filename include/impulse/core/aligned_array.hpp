// impulse/core/aligned_array.hpp — a fixed-capacity array aligned for SIMD loads.
//
// The particle columns (x, y, z, vx, ...) are each one of these: allocated
// once at creation, 64-byte aligned so that a batch never straddles a cache
// line, and never reallocated, so a pointer taken before a step is still
// valid after it. Elements are value-initialised (zero for scalars).
#pragma once

#include <cstddef>
#include <new>
#include <span>
#include <type_traits>
#include <utility>

namespace impulse {

/// Alignment of every particle column: one cache line, and the width of an
/// AVX-512 register.
inline constexpr std::size_t simd_alignment = 64;

template <class T>
  requires std::is_trivially_copyable_v<T> && std::is_trivially_destructible_v<T>
class aligned_array {
 public:
  aligned_array() noexcept = default;
  explicit aligned_array(std::size_t size) : size_(size) {
    if (size == 0) return;
    // size · sizeof(T) would wrap to a small block that the loop below overruns.
    if (size > std::size_t(-1) / sizeof(T)) throw std::bad_array_new_length();
    data_ = static_cast<T*>(::operator new(size * sizeof(T), std::align_val_t{simd_alignment}));
    for (std::size_t i = 0; i < size; ++i) ::new (data_ + i) T();
  }
  aligned_array(const aligned_array& other) : aligned_array(other.size_) {
    if (size_ != 0) __builtin_memcpy(data_, other.data_, size_ * sizeof(T));
  }
  aligned_array(aligned_array&& other) noexcept
      : data_(std::exchange(other.data_, nullptr)), size_(std::exchange(other.size_, 0)) {}
  aligned_array& operator=(aligned_array other) noexcept {
    std::swap(data_, other.data_);
    std::swap(size_, other.size_);
    return *this;
  }
  ~aligned_array() {
    if (data_) ::operator delete(data_, std::align_val_t{simd_alignment});
  }

  [[nodiscard]] std::size_t size() const noexcept { return size_; }
  [[nodiscard]] T* data() noexcept { return data_; }
  [[nodiscard]] const T* data() const noexcept { return data_; }
  T& operator[](std::size_t i) noexcept { return data_[i]; }
  const T& operator[](std::size_t i) const noexcept { return data_[i]; }
  [[nodiscard]] std::span<T> span() noexcept { return {data_, size_}; }
  [[nodiscard]] std::span<const T> span() const noexcept { return {data_, size_}; }

 private:
  T* data_ = nullptr;
  std::size_t size_ = 0;
};

}  // namespace impulse
