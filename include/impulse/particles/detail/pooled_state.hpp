// impulse/particles/detail/pooled_state.hpp — a whole particle system's
// positions (or velocities) as one integrator state.
//
// A system with springs cannot be stepped one batch at a time: the springs
// couple arbitrary particles, so every integrator stage needs every
// particle's stage position before any acceleration can be evaluated. The
// integrators are written once, over any ode_state (integrators/ode_state.hpp),
// so this path hands them a state holding all three columns (x | y | z) of
// every particle, with + and × as loops over them. The temporaries an
// integrator makes (RK4 keeps about a dozen alive) come from a pool of
// buffers allocated on the first step and reused on every later one, so a
// step allocates nothing once warm.
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

#include "../../core/aligned_array.hpp"

namespace impulse::particles::detail {

template <class T>
class column_pool {
 public:
  /// Buffers of 3 × stride values; `used` values of each column are live.
  void resize(std::size_t stride, std::size_t used) {
    if (stride != stride_) {
      buffers_.clear();
      free_.clear();
      stride_ = stride;
    }
    used_ = used;
  }
  [[nodiscard]] std::size_t stride() const noexcept { return stride_; }
  [[nodiscard]] std::size_t used() const noexcept { return used_; }

  std::size_t acquire() {
    if (free_.empty()) {
      buffers_.emplace_back(3 * stride_);
      return buffers_.size() - 1;
    }
    const std::size_t slot = free_.back();
    free_.pop_back();
    return slot;
  }
  void release(std::size_t slot) { free_.push_back(slot); }
  T* data(std::size_t slot) noexcept { return buffers_[slot].data(); }

 private:
  // aligned_array's move keeps its pointer, so growing this vector never
  // invalidates a T* handed out before.
  std::vector<aligned_array<T>> buffers_;
  std::vector<std::size_t> free_;
  std::size_t stride_ = 0, used_ = 0;
};

template <class T>
class pooled_state {
 public:
  explicit pooled_state(column_pool<T>& pool) : pool_(&pool), slot_(pool.acquire()) {}
  pooled_state(const pooled_state& other) : pooled_state(*other.pool_) {
    for_each([&](std::size_t i) { data()[i] = other.data()[i]; });
  }
  pooled_state(pooled_state&& other) noexcept : pool_(other.pool_), slot_(std::exchange(other.slot_, none)) {}
  pooled_state& operator=(pooled_state other) noexcept {
    std::swap(pool_, other.pool_);
    std::swap(slot_, other.slot_);
    return *this;
  }
  ~pooled_state() {
    if (slot_ != none) pool_->release(slot_);
  }

  T* data() noexcept { return pool_->data(slot_); }
  const T* data() const noexcept { return pool_->data(slot_); }
  [[nodiscard]] std::size_t stride() const noexcept { return pool_->stride(); }

  /// Calls f(i) for the index of every live value of the three columns.
  template <class F>
  void for_each(F&& f) const {
    const std::size_t stride = pool_->stride(), used = pool_->used();
    for (std::size_t c = 0; c < 3; ++c)
      for (std::size_t i = c * stride; i < c * stride + used; ++i) f(i);
  }

  // An rvalue operand lends its buffer to the result, so `a + b * h` uses
  // one temporary, not two.
  friend pooled_state operator+(pooled_state&& a, const pooled_state& b) {
    a.for_each([&](std::size_t i) { a.data()[i] += b.data()[i]; });
    return std::move(a);
  }
  friend pooled_state operator+(const pooled_state& a, pooled_state&& b) { return std::move(b) + a; }
  friend pooled_state operator+(pooled_state&& a, pooled_state&& b) { return std::move(a) + b; }
  friend pooled_state operator+(const pooled_state& a, const pooled_state& b) { return pooled_state(a) + b; }
  friend pooled_state operator*(pooled_state&& a, T h) {
    a.for_each([&](std::size_t i) { a.data()[i] *= h; });
    return std::move(a);
  }
  friend pooled_state operator*(const pooled_state& a, T h) { return pooled_state(a) * h; }

 private:
  static constexpr std::size_t none = ~std::size_t(0);
  column_pool<T>* pool_;
  std::size_t slot_;
};

}  // namespace impulse::particles::detail
