// impulse/particles/springs.hpp — damped springs between pairs of particles.
//
// Hooke's law plus damping along the spring (Witkin & Baraff, "Physically
// Based Modeling", SIGGRAPH 2001 course, "Particle system dynamics", §4):
//     f_a = −[k·(|d| − L) + c·(Δv·d̂)]·d̂,   f_b = −f_a,   d = x_a − x_b, Δv = v_a − v_b.
// Damping acts only along d̂, so a spinning pair is not slowed. A spring is
// not lane-parallel (it reads two arbitrary particles), so it runs as its own
// gather/scatter pass over the whole system at every integrator stage: RK4
// with springs evaluates them four times a step, which is what gives it RK4's
// stability limit (docs/particles.md lists the limit per integrator). The
// springs are coloured so that no two of a colour share a particle: workers
// split a colour with no two writing the same value.
#pragma once

#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "../core/task_system.hpp"
#include "force.hpp"

namespace impulse::particles {

template <class T>
struct spring {
  std::uint32_t a = 0, b = 0;  ///< particle indices
  T rest_length = T(1);        ///< L, m, ≥ 0
  T stiffness = T(100);        ///< k, N/m, ≥ 0
  T damping = T(0);            ///< c, N·s/m, ≥ 0
};

template <class T>
struct springs {
  static constexpr force_effect effect = force_effect::pairwise;

  std::vector<spring<T>> list;

  /// Adds a spring between particles a and b; indices are checked against the
  /// system at the next step. Returns the spring's index.
  std::size_t add(std::uint32_t a, std::uint32_t b, T rest_length, T stiffness, T damping = T(0)) {
    const spring<T> s{a, b, rest_length, stiffness, damping};
    check(s, std::uint32_t(list.size()));
    list.push_back(s);
    return list.size() - 1;
  }

  void validate() const {
    for (std::size_t i = 0; i < list.size(); ++i) check(list[i], std::uint32_t(i));
  }
  /// validate(), and every end a live particle (below `particles`), in one
  /// scan split over the task system's workers; the first bad spring in
  /// list order is reported, as one thread would. The particle system calls
  /// this once a step.
  void validate(std::size_t particles, const task_system& tasks) const {
    const std::uint32_t n = std::uint32_t(list.size());
    std::atomic<std::uint32_t> first_bad{n};
    auto scan = [&](std::uint32_t begin, std::uint32_t end, std::uint32_t) {
      for (std::uint32_t i = begin; i < end; ++i)
        if (!valid(list[i], particles)) {
          std::uint32_t seen = first_bad.load(std::memory_order_relaxed);
          while (i < seen && !first_bad.compare_exchange_weak(seen, i, std::memory_order_relaxed)) {
          }
          return;
        }
    };
    impulse::detail::parallel_for(tasks, n, scan_range, scan);
    const std::uint32_t bad = first_bad.load(std::memory_order_relaxed);
    if (bad == n) return;
    check(list[bad], bad);
    detail::require(list[bad].a < particles && list[bad].b < particles, error_code::out_of_range,
                    "springs: a spring names a particle that does not exist", bad);
  }

  // Each spring's force, divided by its particle's mass, is added to its
  // ends' accelerations colour by colour: no two springs of a colour share
  // a particle, so a colour's springs can be split across workers with no
  // two writing the same value, and each particle receives its springs'
  // forces in colour order whatever the split. One thread runs the same
  // colours in the same order, so the sums are the same bits for any
  // worker count. Positions, velocities and accelerations are three
  // columns (x | y | z) of `stride` values each; a null inverse_mass means
  // unit masses.

  /// The most colours. A spring whose ends between them already have all of
  /// them (a particle with more springs than this, say) goes to a last
  /// group, run as one range on one thread.
  static constexpr std::size_t max_colours = 64;

  /// Colours the springs (greedily, each the lowest colour neither end has
  /// yet) and orders them by colour; once a step, before add_forces(). The
  /// colours are kept while no spring's ends change: on a 300 × 300 cloth
  /// the check took 1.3 % of an RK4 step where colouring took 8.9 %. The
  /// check splits over the task system's workers; colouring is in list
  /// order, on one thread.
  void prepare_colours(std::size_t particles, const task_system& tasks = {}) {
    if (coloured_ends_.size() == list.size()) {
      std::atomic<bool> changed{false};
      auto compare = [&](std::uint32_t begin, std::uint32_t end, std::uint32_t) {
        bool differ = false;
        for (std::uint32_t k = begin; k < end; ++k)
          differ |= coloured_ends_[k] != (std::uint64_t(list[k].a) << 32 | list[k].b);
        if (differ) changed.store(true, std::memory_order_relaxed);
      };
      impulse::detail::parallel_for(tasks, std::uint32_t(list.size()), scan_range, compare);
      if (!changed.load(std::memory_order_relaxed)) return;
    }
    coloured_ends_.resize(list.size());
    for (std::size_t k = 0; k < list.size(); ++k) coloured_ends_[k] = std::uint64_t(list[k].a) << 32 | list[k].b;
    taken_.assign(particles, 0);
    colour_.resize(list.size());
    std::array<std::uint32_t, max_colours + 2> count{};
    for (std::size_t k = 0; k < list.size(); ++k) {
      const std::uint64_t taken = taken_[list[k].a] | taken_[list[k].b];
      const unsigned c = taken == ~std::uint64_t(0) ? unsigned(max_colours) : unsigned(std::countr_one(taken));
      if (c < max_colours) taken_[list[k].a] |= std::uint64_t(1) << c, taken_[list[k].b] |= std::uint64_t(1) << c;
      colour_[k] = std::uint8_t(c);
      ++count[c + 1];
    }
    for (std::size_t c = 0; c <= max_colours; ++c) count[c + 1] += count[c];
    colours_ = 0;
    for (std::size_t c = 0; c <= max_colours; ++c) {
      colour_first_[c] = count[c];
      if (count[c + 1] > count[c]) colours_ = c + 1;
    }
    colour_first_[max_colours + 1] = count[max_colours + 1];
    order_.resize(list.size());
    for (std::size_t k = 0; k < list.size(); ++k) order_[count[colour_[k]]++] = std::uint32_t(k);
  }
  /// Colour groups after prepare_colours(): colour c is springs
  /// [colour_begin(c), colour_begin(c + 1)) of the colour order. The last
  /// group, max_colours, is the overflow one.
  [[nodiscard]] std::size_t colour_count() const noexcept { return colours_; }
  [[nodiscard]] std::uint32_t colour_begin(std::size_t c) const noexcept { return colour_first_[c]; }
  [[nodiscard]] static constexpr bool colour_is_shared(std::size_t c) noexcept { return c == max_colours; }

  /// Adds the forces of springs [begin, end) of the colour order to their ends.
  void add_forces(std::size_t begin, std::size_t end, const T* position, const T* velocity,
                  const T* inverse_mass, std::size_t stride, T* acc) const noexcept {
    for (std::size_t j = begin; j < end; ++j) {
      const spring<T>& s = list[order_[j]];
      vec3<T> f;
      if (!force_of(s, position, velocity, stride, f)) continue;
      add_to(acc, stride, s.a, inverse_mass ? f * inverse_mass[s.a] : f);
      add_to(acc, stride, s.b, inverse_mass ? f * -inverse_mass[s.b] : -f);
    }
  }

  /// After particles were moved (index i now at remap[i], or no_object when
  /// it died): follows the moves and drops springs that lost an end.
  void remap(const std::uint32_t* new_index) {
    std::size_t kept = 0;
    for (spring<T> s : list) {
      s.a = new_index[s.a];
      s.b = new_index[s.b];
      if (s.a != no_object && s.b != no_object) list[kept++] = s;
    }
    list.resize(kept);
  }

 private:
  /// The force on s's a end (−f on its b end); false, and f untouched, when
  /// the ends coincide: there is no direction to push along, and the spring
  /// does nothing until they separate (a rest length of 0 is then exact).
  static bool force_of(const spring<T>& s, const T* position, const T* velocity, std::size_t stride,
                       vec3<T>& f) noexcept {
    const vec3<T> d = column_vec(position, stride, s.a) - column_vec(position, stride, s.b);
    const T length = impulse::length(d);
    if (!(length > T(0))) return false;
    const vec3<T> u = d / length;
    const vec3<T> dv = column_vec(velocity, stride, s.a) - column_vec(velocity, stride, s.b);
    f = u * -(s.stiffness * (length - s.rest_length) + s.damping * dot(dv, u));
    return true;
  }

  /// Springs per range of a scan (validation, the colours' check): about
  /// 20 µs of work.
  static constexpr std::uint32_t scan_range = 16384;

  // The rules, once: check() reports the first one a spring breaks, valid()
  // is the scan's quiet test of all of them and of the ends' range.
  static bool finite(const spring<T>& s) noexcept {
    return std::isfinite(s.rest_length) && std::isfinite(s.stiffness) && std::isfinite(s.damping);
  }
  static bool non_negative(const spring<T>& s) noexcept {
    return s.rest_length >= T(0) && s.stiffness >= T(0) && s.damping >= T(0);
  }
  static bool valid(const spring<T>& s, std::size_t particles) noexcept {
    return finite(s) && non_negative(s) && s.a != s.b && s.a < particles && s.b < particles;
  }
  static void check(const spring<T>& s, std::uint32_t index) {
    detail::require(finite(s), error_code::non_finite, "springs: a parameter is not finite", index);
    detail::require(non_negative(s), error_code::invalid_parameter,
                    "springs: rest length, stiffness and damping must be non-negative", index);
    detail::require(s.a != s.b, error_code::invalid_parameter, "springs: both ends are the same particle",
                    index);
  }
  static vec3<T> column_vec(const T* p, std::size_t stride, std::uint32_t i) noexcept {
    return {p[i], p[stride + i], p[2 * stride + i]};
  }
  static void add_to(T* p, std::size_t stride, std::uint32_t i, const vec3<T>& f) noexcept {
    p[i] += f.x;
    p[stride + i] += f.y;
    p[2 * stride + i] += f.z;
  }

  // Scratch of the colouring (prepare_colours), not state.
  std::vector<std::uint64_t> coloured_ends_;  // per spring, a << 32 | b when coloured
  std::vector<std::uint64_t> taken_;          // per particle, the colours its springs have
  std::vector<std::uint8_t> colour_;  // per spring
  std::vector<std::uint32_t> order_;  // the springs by colour, in list order within one
  std::array<std::uint32_t, max_colours + 2> colour_first_{};
  std::size_t colours_ = 0;
};

}  // namespace impulse::particles
