// impulse/particles/springs.hpp — damped springs between pairs of particles.
//
// Hooke's law plus damping along the spring (Witkin & Baraff, "Physically
// Based Modeling", SIGGRAPH 2001 course, "Particle system dynamics", §4):
//     f_a = −[k·(|d| − L) + c·(Δv·d̂)]·d̂,   f_b = −f_a,   d = x_a − x_b, Δv = v_a − v_b.
// Damping acts only along d̂, so a spinning pair is not slowed. A spring is
// not lane-parallel (it reads two arbitrary particles), so it runs as its own
// gather/scatter pass over the whole system at every integrator stage: RK4
// with springs evaluates them four times a step, which is what gives it RK4's
// stability limit (docs/particles.md lists the limit per integrator).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

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
  /// The indices refer to live particles (0 ≤ a, b < count).
  void validate_indices(std::size_t count) const {
    for (std::size_t i = 0; i < list.size(); ++i)
      detail::require(list[i].a < count && list[i].b < count, error_code::out_of_range,
                      "springs: a spring names a particle that does not exist", std::uint32_t(i));
  }

  /// Adds each spring's force, divided by its particle's mass, to acc.
  /// Positions, velocities and accelerations are three columns (x | y | z)
  /// of `stride` values each.
  void accumulate(const T* position, const T* velocity, const T* inverse_mass,
                  std::size_t stride, T* acc) const noexcept {
    for (const spring<T>& s : list) {
      const vec3<T> d = column_vec(position, stride, s.a) - column_vec(position, stride, s.b);
      const T length = impulse::length(d);
      // Coincident endpoints have no direction to push along; the spring
      // does nothing until they separate (a rest length of 0 is then exact).
      if (!(length > T(0))) continue;
      const vec3<T> u = d / length;
      const vec3<T> dv = column_vec(velocity, stride, s.a) - column_vec(velocity, stride, s.b);
      const vec3<T> f = u * -(s.stiffness * (length - s.rest_length) + s.damping * dot(dv, u));
      add_to(acc, stride, s.a, f * inverse_mass[s.a]);
      add_to(acc, stride, s.b, f * -inverse_mass[s.b]);
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
  static void check(const spring<T>& s, std::uint32_t index) {
    detail::require(std::isfinite(s.rest_length) && std::isfinite(s.stiffness) && std::isfinite(s.damping),
                    error_code::non_finite, "springs: a parameter is not finite", index);
    detail::require(s.rest_length >= T(0) && s.stiffness >= T(0) && s.damping >= T(0),
                    error_code::invalid_parameter,
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
};

}  // namespace impulse::particles
