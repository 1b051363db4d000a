// impulse/particles/springs.hpp — damped springs between pairs of particles.
//
// Hooke's law plus damping along the spring (Witkin & Baraff, "Physically
// Based Modeling", SIGGRAPH 2001 course, "Particle system dynamics", §4):
//     f_a = −[k·(|d| − L) + c·(Δv·d̂)]·d̂,   f_b = −f_a,   d = x_a − x_b, Δv = v_a − v_b.
// Damping acts only along d̂, so a spinning pair is not slowed. A spring is
// not lane-parallel (it reads two arbitrary particles), so it runs as its own
// pass over the whole system at every integrator stage: RK4 with springs
// evaluates them four times a step, which is what gives it RK4's stability
// limit (docs/particles.md lists the limit per integrator).
//
// The springs are kept in columns (ends, rest length, stiffness, damping),
// checked as they are added or set, so a step reads them without checking
// them again. A step takes two passes, and workers split both with no two
// writing the same value: each spring's force goes to its own slot, `width`
// springs at a time; then each particle sums its own springs' forces.
#pragma once

#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "../core/task_system.hpp"
#include "../math/vec3_batch.hpp"
#include "force.hpp"

namespace impulse::particles {

namespace detail {

/// Lane i takes base[index[i]]: one gather instruction with AVX-512 or AVX2
/// (the builtins behind _mm512_i32gather_ps and its kin), else lane by lane.
template <scalar_type T>
batch<T> gather(const T* base, const std::uint32_t* index) noexcept {
#if defined(__GNUC__) && (defined(__AVX512F__) || defined(__AVX2__))
  using eight = int __attribute__((vector_size(32)));
  const batch<T> none = batch<T>::broadcast(T(0));
#endif
#if defined(__GNUC__) && defined(__AVX512F__)
  if constexpr (std::is_same_v<T, float>) {
    using sixteen = int __attribute__((vector_size(64)));
    sixteen i;
    __builtin_memcpy(&i, index, sizeof i);
    return {__builtin_ia32_gathersiv16sf(none.v, base, i, static_cast<unsigned short>(0xffff), 4)};
  } else {
    eight i;
    __builtin_memcpy(&i, index, sizeof i);
    return {__builtin_ia32_gathersiv8df(none.v, base, i, static_cast<unsigned char>(0xff), 8)};
  }
#elif defined(__GNUC__) && defined(__AVX2__)
  const batch<T> all = none - T(1);  // the sign of every lane set: gather it
  if constexpr (std::is_same_v<T, float>) {
    eight i;
    __builtin_memcpy(&i, index, sizeof i);
#if defined(__clang__)
    return {__builtin_ia32_gatherd_ps256(none.v, base, i, all.v, 4)};
#else
    return {__builtin_ia32_gathersiv8sf(none.v, base, i, all.v, 4)};
#endif
  } else {
    using four = int __attribute__((vector_size(16)));
    four i;
    __builtin_memcpy(&i, index, sizeof i);
#if defined(__clang__)
    return {__builtin_ia32_gatherd_pd256(none.v, base, i, all.v, 8)};
#else
    return {__builtin_ia32_gathersiv4df(none.v, base, i, all.v, 8)};
#endif
  }
#else
  return batch<T>::gather(base, index);
#endif
}

}  // namespace detail

template <class T>
struct spring {
  std::uint32_t a = 0, b = 0;  ///< particle indices
  T rest_length = T(1);        ///< L, m, ≥ 0
  T stiffness = T(100);        ///< k, N/m, ≥ 0
  T damping = T(0);            ///< c, N·s/m, ≥ 0
};

template <class T>
class springs {
 public:
  static constexpr force_effect effect = force_effect::pairwise;

  /// Adds a spring between particles a and b; its ends are checked against
  /// the system at the next step. Returns the spring's index. Throws,
  /// adding nothing, on a parameter that is not finite or is negative, or
  /// on a spring from a particle to itself.
  std::size_t add(std::uint32_t a, std::uint32_t b, T rest_length, T stiffness, T damping = T(0)) {
    const spring<T> s{a, b, rest_length, stiffness, damping};
    detail::require(size_ < max_springs, error_code::out_of_range, "springs: at most 2^31 springs");
    check(s, std::uint32_t(size_));
    if (size_ == a_.size()) grow();
    ++size_;
    store(size_ - 1, s);
    return size_ - 1;
  }
  /// Replaces spring k, checked as add() checks it; throws, changing
  /// nothing, on a bad spring or an index past the last.
  void set(std::size_t k, const spring<T>& s) {
    detail::require(k < size_, error_code::out_of_range, "springs: no spring has this index",
                    k < no_object ? std::uint32_t(k) : no_object - 1);
    check(s, std::uint32_t(k));
    store(k, s);
  }
  [[nodiscard]] spring<T> operator[](std::size_t k) const noexcept {
    return {a_[k], b_[k], rest_length_[k], stiffness_[k], damping_[k]};
  }
  [[nodiscard]] std::size_t size() const noexcept { return size_; }
  [[nodiscard]] bool empty() const noexcept { return size_ == 0; }
  void clear() noexcept {
    size_ = 0;
    a_.assign(a_.size(), 0);
    b_.assign(b_.size(), 0);
    max_end_ = 0;
    listed_ = false;
  }

  /// Nothing to check: every spring was checked as it was added or set.
  void validate() const noexcept {}
  /// Every end a live particle (below `particles`); the first spring in
  /// list order that is not is reported. Splits over the task system's
  /// workers, and only scans when the largest end seen is too large.
  void validate(std::size_t particles, const task_system& tasks) const {
    if (size_ == 0 || max_end_ < particles) return;
    const std::uint32_t n = std::uint32_t(size_);
    std::atomic<std::uint32_t> first_bad{n};
    auto scan = [&](std::uint32_t begin, std::uint32_t end, std::uint32_t) {
      std::uint32_t k = begin;
      while (k < end && a_[k] < particles && b_[k] < particles) ++k;
      if (k == end) return;
      std::uint32_t seen = first_bad.load(std::memory_order_relaxed);
      while (k < seen && !first_bad.compare_exchange_weak(seen, k, std::memory_order_relaxed)) {
      }
    };
    impulse::detail::parallel_for(tasks, n, scan_range, scan);
    const std::uint32_t bad = first_bad.load(std::memory_order_relaxed);
    detail::require(bad == n, error_code::out_of_range, "springs: a spring names a particle that does not exist", bad);
  }

  /// validate(particles, tasks), then lists each particle's springs (in
  /// list order) if a spring's ends or the particle count changed since
  /// the last call; once a step, before compute_forces(). Throws on an end
  /// past the particles, with no particle changed.
  void prepare(std::size_t particles, const task_system& tasks = {}) {
    if (size_ != 0 && max_end_ >= particles) {
      validate(particles, tasks);
      max_end_ = largest_end();  // a larger end was set, and then replaced
    }
    if (listed_ && first_of_.size() == particles + 1) return;
    first_of_.assign(particles + 1, 0);
    for (std::size_t k = 0; k < size_; ++k) ++first_of_[a_[k] + 1], ++first_of_[b_[k] + 1];
    for (std::size_t i = 0; i < particles; ++i) first_of_[i + 1] += first_of_[i];
    entries_.resize(2 * size_);
    cursor_.assign(first_of_.begin(), first_of_.end() - 1);
    for (std::uint32_t k = 0; k < std::uint32_t(size_); ++k) {
      entries_[cursor_[a_[k]]++] = k << 1;
      entries_[cursor_[b_[k]]++] = k << 1 | 1;
    }
    force_.resize(3 * a_.size());
    listed_ = true;
  }

  /// Lanes of the first pass: springs go `width` at a time.
  static constexpr int width = native_width<T>;
  /// Groups of `width` springs; the last one is padded with springs that
  /// pull on nothing.
  [[nodiscard]] std::size_t groups() const noexcept { return (size_ + width - 1) / width; }

  /// Pass one: the forces of groups [begin, end) of `width` springs, each
  /// spring's into its own slot.
  void compute_forces(std::size_t begin, std::size_t end, const T* position, const T* velocity,
                      std::size_t stride) noexcept {
    const std::size_t n = a_.size();
    T* fx = force_.data();
    for (std::size_t first = begin * width; first < end * width; first += width)
      force(first, position, velocity, stride).store(fx + first, fx + n + first, fx + 2 * n + first);
  }

  /// Pass two: adds to particles [begin, end) their springs' forces (of the
  /// last compute_forces()) divided by their masses.
  void add_forces(std::size_t begin, std::size_t end, const T* inverse_mass, std::size_t stride,
                  T* acc) const noexcept {
    const std::size_t n = a_.size();
    const T* fx = force_.data();
    if (end > first_of_.size() - 1) end = first_of_.size() - 1;
    for (std::size_t i = begin; i < end; ++i) {
      if (first_of_[i + 1] == first_of_[i]) continue;
      vec3<T> sum{};
      for (std::uint32_t e = first_of_[i]; e < first_of_[i + 1]; ++e) {
        const std::uint32_t k = entries_[e] >> 1;
        const vec3<T> f{fx[k], fx[n + k], fx[2 * n + k]};
        sum += (entries_[e] & 1) ? -f : f;
      }
      if (inverse_mass) sum *= inverse_mass[i];
      acc[i] += sum.x;
      acc[stride + i] += sum.y;
      acc[2 * stride + i] += sum.z;
    }
  }

  /// After particles were moved (index i now at remap[i], or no_object when
  /// it died): follows the moves and drops springs that lost an end.
  void remap(const std::uint32_t* new_index) {
    std::size_t kept = 0;
    for (std::size_t k = 0; k < size_; ++k) {
      spring<T> s = (*this)[k];
      s.a = new_index[s.a];
      s.b = new_index[s.b];
      if (s.a != no_object && s.b != no_object) store(kept++, s);
    }
    for (std::size_t k = kept; k < size_; ++k) store(k, spring<T>{0, 0, 0, 0, 0});
    size_ = kept;
    max_end_ = largest_end();
  }

 private:
  /// The forces on the a ends of springs [first, first + width) (−f on
  /// their b ends); zero when the ends coincide (or |d| is not a number):
  /// there is no direction to push along, and the spring does nothing
  /// until they separate (a rest length of 0 is then exact).
  vec3_batch<T> force(std::size_t first, const T* position, const T* velocity, std::size_t stride) const noexcept {
    const std::uint32_t *a = a_.data() + first, *b = b_.data() + first;
    const vec3_batch<T> d = ends(position, stride, a) - ends(position, stride, b);
    const vec3_batch<T> dv = ends(velocity, stride, a) - ends(velocity, stride, b);
    using lanes = batch<T>;
    const lanes length = impulse::length(d), zero = lanes::broadcast(T(0));
    const batch_mask<T, width> apart = zero < length;
    const vec3_batch<T> u = d * (lanes::broadcast(T(1)) / length);
    const lanes stretch = length - lanes::load(rest_length_.data() + first);
    const lanes magnitude = lanes::load(stiffness_.data() + first) * stretch +
                            lanes::load(damping_.data() + first) * dot(dv, u);
    const vec3_batch<T> f = u * -magnitude;
    return {select(apart, f.x, zero), select(apart, f.y, zero), select(apart, f.z, zero)};
  }
  static vec3_batch<T> ends(const T* p, std::size_t stride, const std::uint32_t* index) noexcept {
    return {detail::gather<T>(p, index), detail::gather<T>(p + stride, index),
            detail::gather<T>(p + 2 * stride, index)};
  }

  /// The most springs: an entry of a particle's list holds the index
  /// shifted left by one.
  static constexpr std::size_t max_springs = std::size_t(1) << 31;
  /// Springs per range of the ends' scan: about 20 µs of work.
  static constexpr std::uint32_t scan_range = 16384;

  /// Room for more springs: the columns double, in whole groups, padded
  /// with springs between particle 0 and itself that pull on nothing.
  void grow() {
    const std::size_t room = a_.empty() ? std::size_t(width) : 2 * a_.size();
    a_.resize(room, 0);
    b_.resize(room, 0);
    rest_length_.resize(room, T(0));
    stiffness_.resize(room, T(0));
    damping_.resize(room, T(0));
  }
  void store(std::size_t k, const spring<T>& s) noexcept {
    if (a_[k] != s.a || b_[k] != s.b) listed_ = false;
    a_[k] = s.a;
    b_[k] = s.b;
    rest_length_[k] = s.rest_length;
    stiffness_[k] = s.stiffness;
    damping_[k] = s.damping;
    if (s.a > max_end_) max_end_ = s.a;
    if (s.b > max_end_) max_end_ = s.b;
  }
  std::size_t largest_end() const noexcept {
    std::uint32_t most = 0;
    for (std::size_t k = 0; k < size_; ++k) {
      if (a_[k] > most) most = a_[k];
      if (b_[k] > most) most = b_[k];
    }
    return most;
  }

  static void check(const spring<T>& s, std::uint32_t index) {
    detail::require(std::isfinite(s.rest_length) && std::isfinite(s.stiffness) && std::isfinite(s.damping),
                    error_code::non_finite, "springs: a parameter is not finite", index);
    detail::require(s.rest_length >= T(0) && s.stiffness >= T(0) && s.damping >= T(0), error_code::invalid_parameter,
                    "springs: rest length, stiffness and damping must be non-negative", index);
    detail::require(s.a != s.b, error_code::invalid_parameter, "springs: both ends are the same particle",
                    index);
  }

  // The springs, in columns of whole groups of `width`:
  std::vector<std::uint32_t> a_, b_;
  std::vector<T> rest_length_, stiffness_, damping_;
  std::size_t size_ = 0;
  std::size_t max_end_ = 0;  // at least the largest end; exact after prepare() finds none too large
  // Scratch of the two passes, not state:
  std::vector<T> force_;                 // per spring, x | y | z columns
  std::vector<std::uint32_t> first_of_;  // per particle, its first entry; one more at the end
  std::vector<std::uint32_t> entries_;   // spring << 1, | 1 at its b end; by particle
  std::vector<std::uint32_t> cursor_;    // per particle, while listing
  bool listed_ = false;                  // whether first_of_ and entries_ hold the springs' ends
};

}  // namespace impulse::particles
