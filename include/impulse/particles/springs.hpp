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
//
// Lattices (cloth, ropes, grids of soft bodies) are mostly runs: springs
// whose ends both step by one particle from one spring to the next, as
// (i, i + 1), (i + 1, i + 2), … or (i, i + 320), (i + 1, i + 321), …. When
// the springs are listed (the first step after their ends change), each
// spring from a to b finds its next, a spring from a + 1 to b + 1, among
// the springs listed by their a ends, whatever order they were added in;
// every `width` springs along such a chain form a group whose ends are
// loaded as two plain rows instead of gathered lane by lane (the listing
// is linear in the springs). Runs are cut into pieces of at most a
// block (128 springs), and the pieces are put in the order of their first
// particle, so that splitting the springs and splitting the particles
// across workers give each worker about the same part of the lattice. In
// the second pass a piece adds its forces to rows of particles `width` at
// a time. The springs left over (short runs, the tails of runs, any other
// graph) are gathered and summed one by one. Each particle sums its
// pieces' rows in the pieces' order, then its other springs in list order:
// an order that does not depend on how the workers split the particles.
#pragma once

#include <algorithm>
#include <array>
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
    detail::require(size_ < max_springs, error_code::out_of_range, "springs: at most 2^31 - 64 springs");
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

  /// validate(particles, tasks), then lists the springs (runs, groups and
  /// each particle's springs; see the top of this file) if a spring's ends
  /// or the particle count changed since the last call; once a step,
  /// before compute_forces(). Throws on an end past the particles, with no
  /// particle changed.
  void prepare(std::size_t particles, const task_system& tasks = {}) {
    if (size_ != 0 && max_end_ >= particles) {
      validate(particles, tasks);
      max_end_ = largest_end();  // a larger end was set, and then replaced
    }
    if (listed_ && first_of_.size() == particles + 1) return;
    list(particles);
    listed_ = true;
  }

  /// Lanes of the first pass: springs go `width` at a time.
  static constexpr int width = native_width<T>;
  /// Groups of `width` springs in the first pass, as of the last prepare():
  /// the runs' groups, then the other springs', the last one padded with
  /// springs that pull on nothing.
  [[nodiscard]] std::size_t groups() const noexcept { return slots_ / width; }
  /// How many springs of the last prepare() are in runs' groups.
  [[nodiscard]] std::size_t springs_in_runs() const noexcept { return run_slots_; }

  /// Particles per block of the second pass: the runs that reach a block
  /// are listed with it, and its sums are kept on the stack. A range of
  /// the second pass best starts and ends on a block.
  static constexpr std::size_t block = 128;
  static_assert(block % width == 0);
  /// A state's three columns (x, y, z), for the first pass to read.
  using columns3 = std::array<const T*, 3>;

  /// Pass one: the forces of groups [begin, end) of `width` springs, each
  /// spring's into its own slot, from the particles' positions and
  /// velocities.
  void compute_forces(std::size_t begin, std::size_t end, const columns3& position,
                      const columns3& velocity) noexcept {
    const std::size_t n = slots_;
    T* fx = force_.data();
    for (std::size_t g = begin; g < end; ++g) {
      const std::size_t first = g * width;
      vec3_batch<T> d, dv;
      if (g < run_slots_ / width) {
        const std::uint32_t a = group_ends_[2 * g], b = group_ends_[2 * g + 1];
        d = row(position, a) - row(position, b);
        dv = row(velocity, a) - row(velocity, b);
      } else {
        const std::uint32_t *a = loose_a_.data() + (first - run_slots_), *b = loose_b_.data() + (first - run_slots_);
        d = ends(position, a) - ends(position, b);
        dv = ends(velocity, a) - ends(velocity, b);
      }
      force(first, d, dv).store(fx + first, fx + n + first, fx + 2 * n + first);
    }
  }

  /// Pass two: the forces of their springs (of the last compute_forces()),
  /// divided by their masses, on particles [begin, end) into the three
  /// columns at `acc`, `stride` apart (zero for particles past the last
  /// prepare()).
  void set_accelerations(std::size_t begin, std::size_t end, const T* inverse_mass, std::size_t stride,
                         T* acc) const noexcept {
    const std::size_t n = slots_, asked = end;
    const T* f[3] = {force_.data(), force_.data() + n, force_.data() + 2 * n};
    if (end > first_of_.size() - 1) end = first_of_.size() - 1;
    // The sums go straight into the accelerations, or with masses to
    // divide by, on the stack first.
    alignas(64) T stack[3][block];
    const bool direct = !inverse_mass;
    for (std::size_t low = begin; low < end;) {
      const std::size_t at = low / block, high = std::min(end, (at + 1) * block), count = high - low;
      T* const sum[3] = {direct ? acc + low : stack[0], direct ? acc + stride + low : stack[1],
                         direct ? acc + 2 * stride + low : stack[2]};
      for (T* column : sum) std::fill(column, column + count, T(0));
      for (std::uint32_t e = block_first_[at]; e < block_first_[at + 1]; ++e) {
        const run& r = runs_[spans_[e] >> 1];
        const bool b_end = (spans_[e] & 1) != 0;
        const std::size_t start = b_end ? r.b : r.a, from = std::max(low, start),
                          to = std::min(high, start + r.length);
        if (from >= to) continue;
        for (int j = 0; j < 3; ++j) {
          if (b_end) accumulate<true>(sum[j] + (from - low), f[j] + r.slot + (from - start), to - from);
          else accumulate<false>(sum[j] + (from - low), f[j] + r.slot + (from - start), to - from);
        }
      }
      for (std::size_t i = low; i < high && first_of_[i] < first_of_[high]; ++i)
        for (std::uint32_t e = first_of_[i]; e < first_of_[i + 1]; ++e) {
          const std::uint32_t k = entries_[e] >> 1;
          for (int j = 0; j < 3; ++j) {
            if (entries_[e] & 1) sum[j][i - low] -= f[j][k];
            else sum[j][i - low] += f[j][k];
          }
        }
      for (int j = 0; j < 3 && !direct; ++j)
        for (std::size_t i = 0; i < count; ++i) acc[j * stride + low + i] = sum[j][i] * inverse_mass[low + i];
      low = high;
    }
    for (int j = 0; j < 3; ++j) std::fill(acc + j * stride + std::max(begin, end), acc + j * stride + asked, T(0));
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
  /// The forces on the a ends of slots [first, first + width) (−f on
  /// their b ends), from their ends' separations d and relative velocities
  /// dv; zero when the ends coincide (or |d| is not a number): there is no
  /// direction to push along, and the spring does nothing until they
  /// separate (a rest length of 0 is then exact).
  vec3_batch<T> force(std::size_t first, const vec3_batch<T>& d, const vec3_batch<T>& dv) const noexcept {
    using lanes = batch<T>;
    const lanes length = impulse::length(d), zero = lanes::broadcast(T(0));
    const batch_mask<T, width> apart = zero < length;
    const vec3_batch<T> u = d * (lanes::broadcast(T(1)) / length);
    const lanes stretch = length - lanes::load(slot_rest_length_.data() + first);
    const lanes magnitude = lanes::load(slot_stiffness_.data() + first) * stretch +
                            lanes::load(slot_damping_.data() + first) * dot(dv, u);
    const vec3_batch<T> f = u * -magnitude;
    return {select(apart, f.x, zero), select(apart, f.y, zero), select(apart, f.z, zero)};
  }
  static vec3_batch<T> ends(const columns3& p, const std::uint32_t* index) noexcept {
    return {detail::gather<T>(p[0], index), detail::gather<T>(p[1], index), detail::gather<T>(p[2], index)};
  }
  /// Particles [i, i + width): a run's ends, plain loads.
  static vec3_batch<T> row(const columns3& p, std::uint32_t i) noexcept {
    return vec3_batch<T>::load(p[0] + i, p[1] + i, p[2] + i);
  }
  /// to[i] ∓= from[i] for i < count, `width` at a time.
  template <bool subtract>
  static void accumulate(T* to, const T* from, std::size_t count) noexcept {
    using lanes = batch<T>;
    std::size_t i = 0;
    for (; i + width <= count; i += width) {
      const lanes here = lanes::load(to + i), there = lanes::load(from + i);
      (subtract ? here - there : here + there).store(to + i);
    }
    for (; i < count; ++i) to[i] = subtract ? to[i] - from[i] : to[i] + from[i];
  }

  /// Orders the springs into runs and the rest (see the top of this file),
  /// fills the slots' columns in that order, and lists each block's runs
  /// and each particle's other springs.
  void list(std::size_t particles) {
    const std::uint32_t n = std::uint32_t(size_);
    constexpr std::uint32_t none = ~std::uint32_t(0);
    // The springs by their a ends, in list order (first_of_ and entries_
    // lend their room, and are filled for their own use further down).
    first_of_.assign(particles + 1, 0);
    for (std::uint32_t k = 0; k < n; ++k) ++first_of_[a_[k] + 1];
    for (std::size_t i = 0; i < particles; ++i) first_of_[i + 1] += first_of_[i];
    entries_.resize(n);
    cursor_.assign(first_of_.begin(), first_of_.end() - 1);
    for (std::uint32_t k = 0; k < n; ++k) entries_[cursor_[a_[k]]++] = k;
    // Each spring's next in a run: the first spring in list order, among
    // the first `look` from particle a + 1, that goes to b + 1 and is not
    // already another's next.
    next_.assign(n, none);
    preceded_.assign(n, 0u);
    for (std::uint32_t k = 0; k < n; ++k) {
      const std::size_t a = std::size_t(a_[k]) + 1, b = std::size_t(b_[k]) + 1;
      if (a >= particles) continue;
      for (std::uint32_t e = first_of_[a]; e < std::min(first_of_[a + 1], first_of_[a] + look); ++e)
        if (b_[entries_[e]] == b && !preceded_[entries_[e]]) {
          next_[k] = entries_[e];
          preceded_[entries_[e]] = 1;
          break;
        }
    }
    // The runs: the chains from each spring no other precedes, in list
    // order, cut to whole groups and into pieces of at most a block. The
    // pieces, ordered by the block of their first a, take the first slots:
    // the first pass then splits the springs across the workers about as
    // the second splits the particles, and a worker sums mostly forces it
    // computed.
    cursor_.resize(n);
    found_.clear();
    std::uint32_t chained = 0;
    for (std::uint32_t k = 0; k < n; ++k) {
      if (preceded_[k]) continue;
      const std::uint32_t head = chained;
      for (std::uint32_t j = k; j != none; j = next_[j]) cursor_[chained++] = j;
      for (std::uint32_t t = head; t + width <= chained; t += block) {  // `slot` holds its place in cursor_ for now
        const std::uint32_t length = std::min<std::uint32_t>(block, (chained - t) / width * width);
        found_.push_back({a_[cursor_[t]], b_[cursor_[t]], length, t});
      }
    }
    const std::size_t blocks = (particles + block - 1) / block;
    block_first_.assign(blocks + 1, 0);
    for (const run& r : found_) ++block_first_[r.a / block + 1];
    for (std::size_t at = 0; at < blocks; ++at) block_first_[at + 1] += block_first_[at];
    next_.assign(block_first_.begin(), block_first_.end() - 1);
    runs_.resize(found_.size());
    for (const run& r : found_) runs_[next_[r.a / block]++] = r;
    slot_of_.assign(n, none);
    run_slots_ = 0;
    for (run& r : runs_) {
      for (std::uint32_t t = 0; t < r.length; ++t) slot_of_[cursor_[r.slot + t]] = std::uint32_t(run_slots_ + t);
      r.slot = std::uint32_t(run_slots_);
      run_slots_ += r.length;
    }
    // The other springs, in list order, padded to a whole group.
    std::size_t loose = 0;
    for (std::uint32_t k = 0; k < n; ++k)
      if (slot_of_[k] == none) slot_of_[k] = std::uint32_t(run_slots_ + loose++);
    slots_ = run_slots_ + (loose + width - 1) / width * width;
    loose_a_.assign(slots_ - run_slots_, 0);
    loose_b_.assign(slots_ - run_slots_, 0);
    slot_rest_length_.assign(slots_, T(0));
    slot_stiffness_.assign(slots_, T(0));
    slot_damping_.assign(slots_, T(0));
    for (std::uint32_t k = 0; k < n; ++k) {
      store_slot(k);
      if (slot_of_[k] < run_slots_) continue;
      loose_a_[slot_of_[k] - run_slots_] = a_[k];
      loose_b_[slot_of_[k] - run_slots_] = b_[k];
    }
    group_ends_.clear();
    for (const run& r : runs_)
      for (std::uint32_t t = 0; t < r.length; t += width) {
        group_ends_.push_back(r.a + t);
        group_ends_.push_back(r.b + t);
      }
    // Each particle's other springs, in list order.
    first_of_.assign(particles + 1, 0);
    for (std::uint32_t k = 0; k < n; ++k)
      if (slot_of_[k] >= run_slots_) ++first_of_[a_[k] + 1], ++first_of_[b_[k] + 1];
    for (std::size_t i = 0; i < particles; ++i) first_of_[i + 1] += first_of_[i];
    entries_.resize(first_of_[particles]);
    cursor_.assign(first_of_.begin(), first_of_.end() - 1);
    for (std::uint32_t k = 0; k < n; ++k)
      if (slot_of_[k] >= run_slots_) {
        entries_[cursor_[a_[k]]++] = slot_of_[k] << 1;
        entries_[cursor_[b_[k]]++] = slot_of_[k] << 1 | 1;
      }
    // Each block's pieces of runs, a ends before b ends, in the pieces' order.
    block_first_.assign(blocks + 1, 0);
    auto each_block = [&](auto visit) {
      for (std::uint32_t r = 0; r < std::uint32_t(runs_.size()); ++r)
        for (std::uint32_t side = 0; side < 2; ++side) {
          const std::size_t start = side ? runs_[r].b : runs_[r].a, last = start + runs_[r].length - 1;
          for (std::size_t at = start / block; at <= last / block; ++at) visit(at, r << 1 | side);
        }
    };
    each_block([&](std::size_t at, std::uint32_t) { ++block_first_[at + 1]; });
    for (std::size_t at = 0; at < blocks; ++at) block_first_[at + 1] += block_first_[at];
    spans_.resize(block_first_[blocks]);
    cursor_.assign(block_first_.begin(), block_first_.end() - 1);
    each_block([&](std::size_t at, std::uint32_t span) { spans_[cursor_[at]++] = span; });
    force_.resize(3 * slots_);
  }
  /// Copies spring k's parameters to its slot.
  void store_slot(std::size_t k) noexcept {
    const std::uint32_t slot = slot_of_[k];
    slot_rest_length_[slot] = rest_length_[k];
    slot_stiffness_[slot] = stiffness_[k];
    slot_damping_[slot] = damping_[k];
  }

  /// The most springs: an entry of a particle's list holds a slot (the
  /// springs and a group's padding) shifted left by one.
  static constexpr std::size_t max_springs = (std::size_t(1) << 31) - 64;
  /// Springs per range of the ends' scan: about 20 µs of work.
  static constexpr std::uint32_t scan_range = 16384;
  /// Springs from particle a + 1 looked at for the next in a run of a
  /// spring from a: a hub's thousand springs are not searched a thousand
  /// times.
  static constexpr std::uint32_t look = 16;

  /// Room for more springs: the columns double, the new room holding
  /// springs between particle 0 and itself until add() stores one there.
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
    if (listed_) store_slot(k);  // the same ends: the same slot
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

  // The springs, in list order, in columns (the passes read their copies
  // in the slots' order, below):
  std::vector<std::uint32_t> a_, b_;
  std::vector<T> rest_length_, stiffness_, damping_;
  std::size_t size_ = 0;
  std::size_t max_end_ = 0;  // at least the largest end; exact after prepare() finds none too large
  // The listing of the last prepare(), valid while listed_:
  struct run {             // a piece of a run
    std::uint32_t a, b;      // its first spring's ends
    std::uint32_t length;    // springs, a whole number of groups, at most a block
    std::uint32_t slot;      // its first spring's slot
  };
  std::vector<run> runs_;
  std::vector<std::uint32_t> slot_of_;          // per spring
  std::size_t run_slots_ = 0, slots_ = 0;       // the runs' slots come first; all, padded
  std::vector<std::uint32_t> group_ends_;       // per group of a run, its first a and b
  std::vector<std::uint32_t> loose_a_, loose_b_;  // per slot after the runs'
  std::vector<T> slot_rest_length_, slot_stiffness_, slot_damping_;  // per slot
  std::vector<std::uint32_t> first_of_;     // per particle, its first entry; one more at the end
  std::vector<std::uint32_t> entries_;      // slot << 1, | 1 at its b end, of springs not in runs; by particle
  std::vector<std::uint32_t> block_first_;  // per block of particles, its first span; one more at the end
  std::vector<std::uint32_t> spans_;        // run << 1, | 1 for its b ends; by block, in the runs' order
  std::vector<std::uint32_t> cursor_, next_;  // while listing
  std::vector<std::uint32_t> preceded_;        // while listing: 1 where a spring is another's next
  std::vector<run> found_;                     // while listing: the pieces in the order found
  bool listed_ = false;                     // whether the listing holds the springs' ends
  // Scratch of the two passes, not state:
  std::vector<T> force_;  // per slot, x | y | z columns
};

}  // namespace impulse::particles
