// The exact solve of joint trees (joint_tree.hpp, Baraff 1996): one solve
// leaves every tree joint's rows at rest, whatever the masses; it moves no
// momentum into or out of a tree the world does not hold; its position step
// converges as Newton's method does; and groups with a loop, or tied to the
// world twice, are left to Gauss–Seidel.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "impulse/core/random.hpp"
#include "impulse/dynamics/detail/joint_tree.hpp"

namespace dynamics_joint_tree_tests {

namespace {

using namespace impulse;
using T = double;

/// Bodies 0..n−1 in a random tree: each body i > 0 hangs from a random
/// earlier one by a joint of type i mod 5 (ball, hinge, slider, fixed,
/// rigid distance). Masses 0.1 to 100 kg, so neighbours differ up to 1000
/// times; random orientations, inertias and velocities. Body 0 is static
/// when `tied`.
struct random_tree {
  std::vector<solver_body<T>> bodies;
  std::vector<joint_constraint<T>> joints;

  random_tree(int n, bool tied, std::uint32_t seed) {
    lcg32 random{seed};
    const auto uniform = [&](T lo, T hi) { return random.uniform<T>(lo, hi); };
    const auto direction = [&] {
      const vec3<T> d{uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)};
      return normalize(d + vec3<T>{T(0.01), 0, 0});
    };
    bodies.resize(std::size_t(n));
    for (int i = 0; i < n; ++i) {
      solver_body<T>& b = bodies[std::size_t(i)];
      b.position = {uniform(-3, 3), uniform(-3, 3), uniform(-3, 3)};
      b.orientation = quat<T>::from_axis_angle(direction(), uniform(0, 3));
      if (i == 0 && tied) continue;
      const T mass = std::pow(T(10), uniform(-1, 2));
      const vec3<T> moments{mass * uniform(T(0.01), 1), mass * uniform(T(0.01), 1), mass * uniform(T(0.01), 1)};
      const mat3<T> r = to_mat3(b.orientation);
      b.inverse_mass = 1 / mass;
      b.inverse_inertia = r * mat3<T>::diagonal({1 / moments.x, 1 / moments.y, 1 / moments.z}) * transpose(r);
      b.linear_velocity = direction() * uniform(0, 5);
      b.angular_velocity = direction() * uniform(0, 5);
    }
    for (int i = 1; i < n; ++i) {
      joint_constraint<T> j;
      j.type = joint_type(i % 5);
      j.body_a = std::uint32_t(random.next() % std::uint32_t(i));
      j.body_b = std::uint32_t(i);
      const solver_body<T>& a = bodies[j.body_a];
      const solver_body<T>& b = bodies[j.body_b];
      const vec3<T> anchor = (a.position + b.position) * T(0.5);
      j.local_anchor_a = inverse_rotate(a.orientation, anchor - a.position);
      j.local_anchor_b = inverse_rotate(b.orientation, anchor - b.position);
      if (j.type == joint_type::distance) {
        j.local_anchor_b = inverse_rotate(b.orientation, anchor + direction() * T(0.3) - b.position);
        j.length = T(0.3);
      }
      j.local_axis_a = inverse_rotate(a.orientation, direction());
      j.reference = conjugate(a.orientation) * b.orientation;
      joints.push_back(j);
    }
  }

  std::span<const solver_body<T>> read() const { return bodies; }
  void prepare() {
    for (joint_constraint<T>& j : joints) detail::prepare_joint(read(), j);
  }
  /// The largest speed of any tree joint's holding row.
  T worst_speed() const {
    T worst = 0;
    for (const joint_constraint<T>& j : joints) {
      if (!j.in_tree) continue;
      const detail::holding_rows<T> rows(j);
      const solver_body<T>* ends[2] = {&bodies[j.body_a], &bodies[j.body_b]};
      for (int r = 0; r < rows.count; ++r) {
        T speed = 0;
        for (int s = 0; s < 2; ++s)
          for (int c = 0; c < 3; ++c)
            speed += rows.side[s][r][c] * ends[s]->linear_velocity[c] +
                     rows.side[s][r][3 + c] * ends[s]->angular_velocity[c];
        worst = std::max(worst, std::abs(speed));
      }
    }
    return worst;
  }
  /// The largest of any joint's holding errors, m or rad.
  T worst_error() {
    prepare();
    T worst = 0;
    for (const joint_constraint<T>& j : joints) {
      T error[6] = {};
      detail::holding_rows<T>::errors(j, error);
      for (int r = 0; r < detail::holding_row_count(j); ++r) worst = std::max(worst, std::abs(error[r]));
    }
    return worst;
  }
};

}  // namespace

TEST_CASE("one exact solve brings every row of a random joint tree to rest at mass ratios up to 1000") {
  for (std::uint32_t seed = 1; seed <= 20; ++seed) {
    random_tree tree(30, seed % 2 == 0, seed);
    tree.prepare();
    detail::joint_tree<T> solver;
    solver.build(tree.read(), tree.joints);
    for (const joint_constraint<T>& j : tree.joints) REQUIRE(j.in_tree);
    REQUIRE(solver.factor(tree.read(), tree.joints));
    T before = 0;
    for (const solver_body<T>& b : tree.bodies) before = std::max(before, length(b.linear_velocity));
    solver.solve_velocities(tree.bodies, tree.joints);
    // Rounding only: speeds of up to 5 m/s and 5 rad/s brought to 1e-9.
    CHECK(tree.worst_speed() < 1e-9 * before);
  }
}

TEST_CASE("the exact solve of a tree the world does not hold keeps its momentum and angular momentum") {
  // The joints' impulses are internal: equal and opposite at each joint,
  // they leave P = Σ m·v and L = Σ (x × m·v + I·ω) as they were.
  random_tree tree(25, false, 7);
  const auto momenta = [&] {
    vec3<T> p{}, l{};
    for (const solver_body<T>& b : tree.bodies) {
      const vec3<T> mv = b.linear_velocity * (1 / b.inverse_mass);
      p += mv;
      l += cross(b.position, mv) + inverse(b.inverse_inertia) * b.angular_velocity;
    }
    return std::pair{p, l};
  };
  const auto [p0, l0] = momenta();
  tree.prepare();
  detail::joint_tree<T> solver;
  solver.build(tree.read(), tree.joints);
  REQUIRE(solver.factor(tree.read(), tree.joints));
  solver.solve_velocities(tree.bodies, tree.joints);
  const auto [p1, l1] = momenta();
  CHECK(tree.worst_speed() < 1e-9);
  CHECK(length(p1 - p0) < 1e-10 * length(p0) + 1e-10);
  CHECK(length(l1 - l0) < 1e-10 * length(l0) + 1e-10);
}

TEST_CASE("the position step of a joint tree converges quadratically as Newton's method") {
  // The bodies pushed off their joints by up to 2 cm and 0.02 rad; each
  // step removes the linearised error, so what is left is of the order of
  // the error squared.
  random_tree tree(30, true, 11);
  lcg32 random{99};
  for (std::size_t i = 1; i < tree.bodies.size(); ++i) {
    solver_body<T>& b = tree.bodies[i];
    b.position += vec3<T>{random.uniform<T>(-1, 1), random.uniform<T>(-1, 1), random.uniform<T>(-1, 1)} * T(0.01);
    b.orientation = integrate(
        b.orientation, vec3<T>{random.uniform<T>(-1, 1), random.uniform<T>(-1, 1), random.uniform<T>(-1, 1)} * T(0.01),
        T(1));
  }
  detail::joint_tree<T> solver;
  tree.prepare();
  solver.build(tree.read(), tree.joints);
  std::vector<T> errors{tree.worst_error()};
  for (int step = 0; step < 3; ++step) {
    tree.prepare();
    REQUIRE(solver.factor(tree.read(), tree.joints));
    solver.project(tree.bodies, tree.joints);
    errors.push_back(tree.worst_error());
  }
  MESSAGE("largest joint error by Newton step: " << errors[0] << ", " << errors[1] << ", " << errors[2] << ", "
                                                 << errors[3]);
  CHECK(errors[0] > 0.005);
  for (int step = 1; step <= 2; ++step) CHECK(errors[std::size_t(step)] < 10 * errors[std::size_t(step - 1)] * errors[std::size_t(step - 1)]);
  CHECK(errors[3] < 1e-9);
}

TEST_CASE("joints that close a loop or tie a group to the world twice leave the whole group to Gauss-Seidel") {
  // Group one: a floating random tree of bodies 0..11 (joints 0..10).
  // Group two: a static body 12 and a chain 13..16 hanging from it
  // (joints 11..14).
  random_tree tree(12, false, 3);
  solver_body<T> anchor;
  anchor.position = {0, 0, 10};
  tree.bodies.push_back(anchor);
  for (int i = 0; i < 4; ++i) {
    solver_body<T> b = tree.bodies[1];
    b.position = anchor.position + vec3<T>{0, T(-1 - i), 0};
    tree.bodies.push_back(b);
    joint_constraint<T> j;
    j.body_a = std::uint32_t(tree.bodies.size() - 2);
    j.body_b = std::uint32_t(tree.bodies.size() - 1);
    tree.joints.push_back(j);
  }
  detail::joint_tree<T> solver;
  const auto count_in_tree = [&](std::size_t first, std::size_t last) {
    std::size_t n = 0;
    for (std::size_t k = first; k < last; ++k) n += tree.joints[k].in_tree ? 1 : 0;
    return n;
  };
  solver.build(tree.read(), tree.joints);
  CHECK(count_in_tree(0, 15) == 15);

  joint_constraint<T> extra;
  SUBCASE("a loop in group one") {
    extra.body_a = 3, extra.body_b = 9;
    tree.joints.push_back(extra);
    solver.build(tree.read(), tree.joints);
    CHECK(count_in_tree(0, 11) == 0);
    CHECK(count_in_tree(11, 15) == 4);
  }
  SUBCASE("group two tied to the world twice") {
    extra.body_a = 12, extra.body_b = 15;
    tree.joints.push_back(extra);
    solver.build(tree.read(), tree.joints);
    CHECK(count_in_tree(0, 11) == 11);
    CHECK(count_in_tree(11, 15) == 0);
  }
  SUBCASE("a spring closing a loop holds nothing rigidly and changes nothing") {
    extra.type = joint_type::distance;
    extra.spring_hertz = 5;
    extra.body_a = 3, extra.body_b = 9;
    tree.joints.push_back(extra);
    solver.build(tree.read(), tree.joints);
    CHECK(count_in_tree(0, 15) == 15);
  }
  CHECK_FALSE(tree.joints.back().in_tree);
}

}  // namespace dynamics_joint_tree_tests
