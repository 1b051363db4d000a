// impulse/core/detail/pooled_state.hpp — a whole system's state as one
// integrator state, with temporaries drawn from a pool.
//
// Some systems cannot be stepped one element at a time: springs between
// particles or between bodies couple arbitrary elements, so every integrator
// stage needs every element's stage state before any force can be
// evaluated. The integrators are written once, over any ode_state
// (integrators/ode_state.hpp), so these systems hand them a state holding
// every element, with + and × as loops. The temporaries an integrator makes
// (RK4 keeps about a dozen alive) come from a pool of buffers allocated on
// the first step and reused on every later one, so a step allocates nothing
// once warm.
//
// A buffer is `segments` runs of `stride` elements of which the first `used`
// are live: the particle system keeps its x, y and z columns (3 segments of
// scalars), a world without collision one run of poses or momenta.
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

#include "../aligned_array.hpp"
#include "../task_system.hpp"

namespace impulse::detail {

template <class E>
class buffer_pool {
 public:
  void resize(std::size_t segments, std::size_t stride, std::size_t used) {
    if (segments != segments_ || stride != stride_) {
      buffers_.clear();
      free_.clear();
      segments_ = segments;
      stride_ = stride;
    }
    used_ = used;
  }
  [[nodiscard]] std::size_t segments() const noexcept { return segments_; }
  [[nodiscard]] std::size_t stride() const noexcept { return stride_; }
  [[nodiscard]] std::size_t used() const noexcept { return used_; }
  /// Workers to split the states' arithmetic across, or null for this thread.
  void set_tasks(const task_system* tasks) noexcept { tasks_ = tasks; }
  [[nodiscard]] const task_system* tasks() const noexcept { return tasks_; }

  std::size_t acquire() {
    if (free_.empty()) {
      buffers_.emplace_back(segments_ * stride_);
      return buffers_.size() - 1;
    }
    const std::size_t slot = free_.back();
    free_.pop_back();
    return slot;
  }
  void release(std::size_t slot) { free_.push_back(slot); }
  E* data(std::size_t slot) noexcept { return buffers_[slot].data(); }

 private:
  // aligned_array's move keeps its pointer, so growing this vector never
  // invalidates an E* handed out before.
  std::vector<aligned_array<E>> buffers_;
  std::vector<std::size_t> free_;
  std::size_t segments_ = 0, stride_ = 0, used_ = 0;
  const task_system* tasks_ = nullptr;
};

/// E needs E + E and E * S for the scalar S the integrator steps with.
template <class E>
class pooled_state {
 public:
  /// A buffer from the pool, its contents as its last user left them.
  explicit pooled_state(buffer_pool<E>& pool) : pool_(&pool), slot_(pool.acquire()) {}
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

  E* data() noexcept { return pool_->data(slot_); }
  const E* data() const noexcept { return pool_->data(slot_); }
  E& operator[](std::size_t i) noexcept { return data()[i]; }
  const E& operator[](std::size_t i) const noexcept { return data()[i]; }
  [[nodiscard]] std::size_t stride() const noexcept { return pool_->stride(); }

  /// Calls f(i) for the index of every live element of every segment,
  /// split across the pool's workers when it has them: each element's
  /// result is the same whoever computes it.
  template <class F>
  void for_each(F&& f) const {
    const std::size_t segments = pool_->segments(), stride = pool_->stride();
    auto range = [&](std::size_t begin, std::size_t end, std::uint32_t) {
      for (std::size_t s = 0; s < segments; ++s)
        for (std::size_t i = s * stride + begin; i < s * stride + end; ++i) f(i);
    };
    if (const task_system* tasks = pool_->tasks()) parallel_for(*tasks, std::uint32_t(pool_->used()), 4096, range);
    else range(0, pool_->used(), 0);
  }

  // An rvalue operand lends its buffer to the result, so `a + b * h` uses
  // one temporary, not two. Two lvalues are summed (or one scaled) into a
  // fresh buffer in one pass, not copied and then summed: RK4's stages are
  // mostly this, and on a large system each pass is a trip through memory.
  friend pooled_state operator+(pooled_state&& a, const pooled_state& b) {
    a.for_each([&](std::size_t i) { a.data()[i] = a.data()[i] + b.data()[i]; });
    return std::move(a);
  }
  friend pooled_state operator+(const pooled_state& a, pooled_state&& b) { return std::move(b) + a; }
  friend pooled_state operator+(pooled_state&& a, pooled_state&& b) { return std::move(a) + b; }
  friend pooled_state operator+(const pooled_state& a, const pooled_state& b) {
    pooled_state sum(*a.pool_);
    sum.for_each([&](std::size_t i) { sum.data()[i] = a.data()[i] + b.data()[i]; });
    return sum;
  }
  template <class S>
  friend pooled_state operator*(pooled_state&& a, S h) {
    a.for_each([&](std::size_t i) { a.data()[i] = a.data()[i] * h; });
    return std::move(a);
  }
  template <class S>
  friend pooled_state operator*(const pooled_state& a, S h) {
    pooled_state product(*a.pool_);
    product.for_each([&](std::size_t i) { product.data()[i] = a.data()[i] * h; });
    return product;
  }

 private:
  static constexpr std::size_t none = ~std::size_t(0);
  buffer_pool<E>* pool_;
  std::size_t slot_;
};

}  // namespace impulse::detail
