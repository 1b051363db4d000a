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
#include <optional>
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

template <class E, class S>
class scaled_state;

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

  // An rvalue operand lends its buffer to the result, and a product by a
  // scalar is not worked out on its own but where it is summed: `a + b * h`
  // is one pass over the state into one buffer, not two. On a large system
  // each pass is a trip through memory and, across workers, a wait for the
  // slowest: RK4's stages are mostly this, and it took 28 passes a step
  // where it now takes 16.
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
  friend scaled_state<E, S> operator*(const pooled_state& a, S h) {
    return {a, h};
  }
  template <class S>
  friend scaled_state<E, S> operator*(pooled_state&& a, S h) {
    return {std::move(a), h};
  }

 private:
  template <class, class>
  friend class scaled_state;
  static constexpr std::size_t none = ~std::size_t(0);
  buffer_pool<E>* pool_;
  std::size_t slot_;
};

/// A state times a scalar, worked out where it is used: summed into a
/// state (one pass: a[i] + b[i]·h), or made a state of its own. It holds
/// the state it scales by reference, or, scaling a temporary, holds that
/// temporary and reuses its buffer. Made only by pooled_state's operator*
/// and used in the same expression.
template <class E, class S>
class scaled_state {
 public:
  scaled_state(const pooled_state<E>& source, S h) : source_(&source), h_(h) {}
  scaled_state(pooled_state<E>&& source, S h) : owned_(std::move(source)), source_(&*owned_), h_(h) {}
  scaled_state(const scaled_state&) = delete;
  scaled_state& operator=(const scaled_state&) = delete;

  operator pooled_state<E>() && {
    const E* b = source_->data();
    pooled_state<E> result = take_buffer();
    result.for_each([&](std::size_t i) { result.data()[i] = b[i] * h_; });
    return result;
  }

  friend pooled_state<E> operator+(pooled_state<E>&& a, scaled_state&& b) {
    const E* s = b.source_->data();
    a.for_each([&](std::size_t i) { a.data()[i] = a.data()[i] + s[i] * b.h_; });
    return std::move(a);
  }
  friend pooled_state<E> operator+(const pooled_state<E>& a, scaled_state&& b) {
    const E* s = b.source_->data();
    pooled_state<E> result = b.take_buffer();
    result.for_each([&](std::size_t i) { result.data()[i] = a.data()[i] + s[i] * b.h_; });
    return result;
  }
  friend pooled_state<E> operator+(scaled_state&& a, const pooled_state<E>& b) { return b + std::move(a); }
  friend pooled_state<E> operator+(scaled_state&& a, pooled_state<E>&& b) { return std::move(b) + std::move(a); }

 private:
  /// The held temporary's buffer (each element is read before it is
  /// written, so the result may overwrite it), or a fresh one. The
  /// source's data must be read first: the held temporary is moved out.
  pooled_state<E> take_buffer() {
    if (owned_) return std::move(*owned_);
    return pooled_state<E>(*source_->pool_);
  }

  std::optional<pooled_state<E>> owned_;
  const pooled_state<E>* source_;
  S h_;
};

}  // namespace impulse::detail
