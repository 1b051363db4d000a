// The batched contact solver: the coloring never puts two contacts that
// move the same body in one batch, and W contacts solved in lanes give what
// the one-by-one rows of contact_rows.hpp give.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "impulse/core/random.hpp"
#include "impulse/dynamics/detail/constraint_graph.hpp"
#include "impulse/dynamics/detail/contact_batch.hpp"
#include "impulse/dynamics/detail/contact_rows.hpp"

namespace dynamics_contact_batch_tests {

namespace {

using namespace impulse;

template <class T>
solver_body<T> moving_body(T inverse_mass, vec3<T> inertia_diagonal, vec3<T> v, vec3<T> w) {
  solver_body<T> b;
  b.inverse_mass = inverse_mass;
  b.inverse_inertia = mat3<T>::diagonal(inertia_diagonal);
  b.linear_velocity = v;
  b.angular_velocity = w;
  return b;
}

template <class T>
contact_constraint<T> contact_between(std::uint32_t a, std::uint32_t b) {
  contact_constraint<T> c;
  c.body_a = a, c.body_b = b;
  return c;
}

/// Every contact once, no batch wider than `width`, and no moving body
/// twice in a batch.
template <class T>
void check_batches(const detail::constraint_graph& graph, std::span<const solver_body<T>> bodies,
                   std::span<const contact_constraint<T>> contacts, int width) {
  std::vector<int> seen(contacts.size(), 0);
  for (std::size_t k = 0; k < graph.batch_count(); ++k) {
    const auto members = graph.batch(k);
    CHECK(members.size() >= 1);
    CHECK(int(members.size()) <= width);
    std::vector<int> uses(bodies.size(), 0);
    for (const std::uint32_t i : members) {
      ++seen[i];
      for (const std::uint32_t body : {contacts[i].body_a, contacts[i].body_b})
        if (bodies[body].inverse_mass > T(0)) ++uses[body];
    }
    for (const int u : uses) CHECK(u <= 1);
  }
  for (const std::uint32_t i : graph.leftover()) ++seen[i];
  for (const int s : seen) CHECK(s == 1);
}

}  // namespace

TEST_CASE("contacts of one batch never share a moving body") {
  using T = float;
  // 200 bodies, the first 10 static; 1500 contacts between random pairs.
  std::vector<solver_body<T>> bodies(200);
  for (std::size_t i = 10; i < bodies.size(); ++i) bodies[i].inverse_mass = T(1);
  lcg32 random;
  std::vector<contact_constraint<T>> contacts;
  while (contacts.size() < 1500) {
    const std::uint32_t a = random.next() % 200, b = random.next() % 200;
    if (a == b) continue;
    contacts.push_back(contact_between<T>(a, b));
  }
  detail::constraint_graph graph;
  for (const int width : {1, 4, 8, 16}) {
    graph.build(std::span<const solver_body<T>>(bodies), std::span<const contact_constraint<T>>(contacts), width);
    check_batches<T>(graph, bodies, contacts, width);
    CHECK(graph.leftover().empty());
  }
}

TEST_CASE("within a color the contacts follow their first moving body, so a worker's range keeps its bodies") {
  using T = float;
  // 300 bodies, every tenth static; 2000 contacts between random pairs, in
  // random order.
  std::vector<solver_body<T>> bodies(300);
  for (std::size_t i = 0; i < bodies.size(); ++i) bodies[i].inverse_mass = i % 10 == 0 ? T(0) : T(1);
  lcg32 random;
  std::vector<contact_constraint<T>> contacts;
  while (contacts.size() < 2000) {
    const std::uint32_t a = random.next() % 300, b = random.next() % 300;
    if (a == b || (a % 10 == 0 && b % 10 == 0)) continue;
    contacts.push_back(contact_between<T>(a, b));
  }
  const auto first_moving = [&](std::uint32_t i) {
    const std::uint32_t a = contacts[i].body_a, b = contacts[i].body_b;
    if (bodies[a].inverse_mass == T(0)) return b;
    if (bodies[b].inverse_mass == T(0)) return a;
    return std::min(a, b);
  };
  detail::constraint_graph graph;
  graph.build(std::span<const solver_body<T>>(bodies), std::span<const contact_constraint<T>>(contacts), 8);
  check_batches<T>(graph, bodies, contacts, 8);
  REQUIRE(graph.color_count() > 2);
  // A moving body has at most one contact in a color, so the first
  // moving bodies rise strictly through it.
  for (std::size_t q = 0; q < graph.color_count(); ++q) {
    bool first = true;
    std::uint32_t last = 0;
    for (std::uint32_t k = graph.first_batch(q); k < graph.first_batch(q + 1); ++k)
      for (const std::uint32_t i : graph.batch(k)) {
        const std::uint32_t body = first_moving(i);
        CHECK((first || body > last));
        first = false, last = body;
      }
  }
}

TEST_CASE("contacts on a static body share its color and a body in more than 64 contacts leaves some over") {
  using T = float;
  // 100 boxes on the ground (body 0, static): one color, batches of 8.
  std::vector<solver_body<T>> bodies(101);
  for (std::size_t i = 1; i < bodies.size(); ++i) bodies[i].inverse_mass = T(1);
  std::vector<contact_constraint<T>> contacts;
  for (std::uint32_t i = 1; i <= 100; ++i) contacts.push_back(contact_between<T>(0, i));
  detail::constraint_graph graph;
  graph.build(std::span<const solver_body<T>>(bodies), std::span<const contact_constraint<T>>(contacts), 8);
  CHECK(graph.batch_count() == 13);  // 12 full batches and one of 4
  check_batches<T>(graph, bodies, contacts, 8);

  // Body 1 made dynamic-on-dynamic with all the others: 99 contacts on
  // one moving body, 64 of which take a color.
  contacts.clear();
  for (std::uint32_t i = 2; i <= 100; ++i) contacts.push_back(contact_between<T>(1, i));
  graph.build(std::span<const solver_body<T>>(bodies), std::span<const contact_constraint<T>>(contacts), 8);
  CHECK(graph.batch_count() == 64);
  CHECK(graph.leftover().size() == 99 - 64);
  check_batches<T>(graph, bodies, contacts, 8);
}

/// Body 0 is static and shared by every lane; lane l presses body l + 1
/// onto it with l % 4 + 1 points, at random offsets, depths, inertias and
/// velocities.
template <class T, int W>
void lanes_on_a_static_body(std::vector<solver_body<T>>& bodies, std::vector<contact_constraint<T>>& contacts) {
  lcg32 random;
  const auto uniform = [&](T lo, T hi) { return random.uniform<T>(lo, hi); };
  const auto vector = [&](T lo, T hi) { return vec3<T>{uniform(lo, hi), uniform(lo, hi), uniform(lo, hi)}; };
  bodies.push_back(solver_body<T>{});
  for (int l = 0; l < W; ++l) {
    bodies.push_back(moving_body<T>(uniform(T(0.2), T(2)), vector(T(0.5), T(3)), vector(T(-1), T(1)),
                                    vector(T(-2), T(2))));
    contact_constraint<T> c = contact_between<T>(0, std::uint32_t(l + 1));
    c.normal = normalize(vec3<T>{uniform(T(-0.3), T(0.3)), T(1), uniform(T(-0.3), T(0.3))});
    tangents_of(c.normal, c.tangent1, c.tangent2);
    c.friction = T(0.6);
    c.count = l % 4 + 1;
    vec3<T> middle{};
    for (int i = 0; i < c.count; ++i) {
      const vec3<T> at = vector(T(-0.5), T(0.5));
      c.points[i].offset_a = at;
      c.points[i].offset_b = at - vec3<T>{0, T(0.5), 0};
      c.points[i].depth = uniform(T(-0.01), T(0.01));
      c.points[i].normal_impulse = uniform(T(0), T(0.5));
      middle += at;
    }
    middle = middle * (T(1) / T(c.count));
    c.anchor_a = middle, c.anchor_b = middle - vec3<T>{0, T(0.5), 0};
    c.twist_radius = T(0.3);
    c.tangent_impulse1 = uniform(T(-0.1), T(0.1));
    contacts.push_back(c);
  }
}

TEST_CASE_TEMPLATE("contacts solved in lanes match the rows solved one by one", T, float, double) {
  constexpr int W = detail::contact_lanes<T>;
  constexpr int sweeps = 4;
  std::vector<solver_body<T>> bodies;
  std::vector<contact_constraint<T>> contacts;
  lanes_on_a_static_body<T, W>(bodies, contacts);
  const T inverse_dt = T(60), rest_depth = T(3e-6);
  for (contact_constraint<T>& c : contacts)
    for (int i = 0; i < c.count; ++i)
      c.points[i].gap_speed = std::max(rest_depth - c.points[i].depth, T(0)) * inverse_dt;
  detail::prepare_contacts(std::span<const solver_body<T>>(bodies), std::span<contact_constraint<T>>(contacts));

  // One by one: friction, then the normal rows `sweeps` times.
  std::vector<solver_body<T>> one = bodies;
  std::vector<contact_constraint<T>> by_row = contacts;
  for (int iteration = 0; iteration < 3; ++iteration)
    for (contact_constraint<T>& c : by_row) {
      solver_body<T>& a = one[c.body_a];
      solver_body<T>& b = one[c.body_b];
      detail::solve_friction(a, b, c);
      for (int sweep = 0; sweep < sweeps; ++sweep)
        for (int i = 0; i < c.count; ++i) {
          contact_constraint_point<T>& p = c.points[i];
          detail::solve_normal(a.linear_velocity, a.angular_velocity, b.linear_velocity, b.angular_velocity, a, b,
                               c.normal, p, p.normal_impulse, p.gap_speed);
        }
    }

  // In lanes.
  std::vector<solver_body<T>> lanes = bodies;
  std::vector<contact_constraint<T>> batched = contacts;
  std::vector<std::uint32_t> members;
  for (int l = 0; l < W; ++l) members.push_back(std::uint32_t(l));
  detail::contact_batch<T, W> batch;
  std::vector<detail::batch_row<T, W>> rows;
  detail::load_batch(std::span<const solver_body<T>>(lanes), std::span<const contact_constraint<T>>(batched),
                     std::span<const std::uint32_t>(members), batch, rows);
  const auto own = std::span<detail::batch_row<T, W>>(rows);
  constexpr auto real = detail::velocity_kind::real;
  for (int iteration = 0; iteration < 3; ++iteration) {
    auto v = detail::gather(std::span<const solver_body<T>>(lanes), batch, real);
    detail::solve_batch_friction(v, batch, std::span<const detail::batch_row<T, W>>(own));
    detail::solve_batch_normals<detail::normal_pass::velocity>(v, batch, own, sweeps);
    detail::scatter(std::span<solver_body<T>>(lanes), batch, v, real);
  }
  detail::store_batch(batch, std::span<const detail::batch_row<T, W>>(own), std::span<contact_constraint<T>>(batched));

  // Same rows, summed in another order: equal to rounding over a few
  // dozen operations.
  const T tolerance = std::is_same_v<T, float> ? T(2e-4) : T(1e-11);
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    CHECK(length(one[i].linear_velocity - lanes[i].linear_velocity) < tolerance);
    CHECK(length(one[i].angular_velocity - lanes[i].angular_velocity) < tolerance);
  }
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    for (int i = 0; i < contacts[k].count; ++i)
      CHECK(std::abs(by_row[k].points[i].normal_impulse - batched[k].points[i].normal_impulse) < tolerance);
    CHECK(std::abs(by_row[k].tangent_impulse1 - batched[k].tangent_impulse1) < tolerance);
    CHECK(std::abs(by_row[k].tangent_impulse2 - batched[k].tangent_impulse2) < tolerance);
    CHECK(std::abs(by_row[k].twist_impulse - batched[k].twist_impulse) < tolerance);
  }
  // The static body is shared by every lane and is left as it was.
  CHECK(lanes[0].linear_velocity == vec3<T>{});
  CHECK(lanes[0].angular_velocity == vec3<T>{});
}

TEST_CASE_TEMPLATE("soft_step's soft and relax sweeps in lanes match the rows solved one by one", T, float, double) {
  constexpr int W = detail::contact_lanes<T>;
  constexpr int sweeps = 2;
  std::vector<solver_body<T>> bodies;
  std::vector<contact_constraint<T>> contacts;
  lanes_on_a_static_body<T, W>(bodies, contacts);
  detail::prepare_contacts(std::span<const solver_body<T>>(bodies), std::span<contact_constraint<T>>(contacts));
  // Every body has moved and turned a little since the contacts were found.
  lcg32 random;
  std::vector<detail::body_displacement<T>> moved(bodies.size());
  for (std::size_t i = 1; i < moved.size(); ++i) {
    moved[i].linear = {random.uniform<T>(T(-0.004), T(0.004)), random.uniform<T>(T(-0.004), T(0.004)), T(0)};
    moved[i].angular = {random.uniform<T>(T(-0.01), T(0.01)), T(0), random.uniform<T>(T(-0.01), T(0.01))};
  }
  const T h = T(1) / T(240), slop = T(0.0005), fastest = T(3);
  const softness<T> moving = soften(T(30), T(10), h), fixed = soften(T(60), T(10), h);

  std::vector<std::uint32_t> members;
  for (int l = 0; l < W; ++l) members.push_back(std::uint32_t(l));
  for (const bool push : {true, false}) {
    // One by one: the depth now, the target the rule asks, and the rows.
    std::vector<solver_body<T>> one = bodies;
    std::vector<contact_constraint<T>> by_row = contacts;
    for (contact_constraint<T>& c : by_row) {
      solver_body<T>& a = one[c.body_a];
      solver_body<T>& b = one[c.body_b];
      for (int i = 0; i < c.count; ++i) {
        contact_constraint_point<T>& p = c.points[i];
        const T depth = detail::depth_now(c, p, std::span<const detail::body_displacement<T>>(moved));
        // Apart: close the gap within the substep; else, in the soft
        // sweep, push out at the static contact's rate beyond the slop.
        p.gap_speed = std::max(-depth, T(0)) / h;
        const T soft_push = std::min(fixed.bias_rate * std::max(depth - slop, T(0)), fastest);
        p.push_speed = depth < T(0) || !push ? T(0) : soft_push;
      }
      for (int sweep = 0; sweep < sweeps; ++sweep)
        for (int i = 0; i < c.count; ++i) {
          contact_constraint_point<T>& p = c.points[i];
          const bool soft = push && p.gap_speed <= T(0);
          detail::solve_normal(a.linear_velocity, a.angular_velocity, b.linear_velocity, b.angular_velocity, a, b,
                               c.normal, p, p.normal_impulse, p.gap_speed - p.push_speed,
                               soft ? fixed.mass_scale : T(1), soft ? fixed.impulse_scale : T(0));
        }
    }
    // In lanes.
    std::vector<solver_body<T>> lanes = bodies;
    std::vector<contact_constraint<T>> batched = contacts;
    detail::contact_batch<T, W> batch;
    std::vector<detail::batch_row<T, W>> rows;
    detail::load_batch(std::span<const solver_body<T>>(lanes), std::span<const contact_constraint<T>>(batched),
                       std::span<const std::uint32_t>(members), batch, rows);
    detail::soften_batch(batch, moving, fixed);
    const auto own = std::span<detail::batch_row<T, W>>(rows);
    detail::soft_targets_batch(batch, own, std::span<const detail::body_displacement<T>>(moved), slop, fastest,
                               T(1) / h);
    constexpr auto real = detail::velocity_kind::real;
    auto v = detail::gather(std::span<const solver_body<T>>(lanes), batch, real);
    if (push)
      detail::solve_batch_normals<detail::normal_pass::soft>(v, batch, own, sweeps);
    else
      detail::solve_batch_normals<detail::normal_pass::relax>(v, batch, own, sweeps);
    detail::scatter(std::span<solver_body<T>>(lanes), batch, v, real);
    detail::store_batch(batch, std::span<const detail::batch_row<T, W>>(own),
                        std::span<contact_constraint<T>>(batched));

    // The same rows, summed in another order: equal to rounding.
    const T tolerance = std::is_same_v<T, float> ? T(2e-4) : T(1e-11);
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      CHECK(length(one[i].linear_velocity - lanes[i].linear_velocity) < tolerance);
      CHECK(length(one[i].angular_velocity - lanes[i].angular_velocity) < tolerance);
    }
    for (std::size_t k = 0; k < contacts.size(); ++k)
      for (int i = 0; i < contacts[k].count; ++i)
        CHECK(std::abs(by_row[k].points[i].normal_impulse - batched[k].points[i].normal_impulse) < tolerance);
  }
}

}  // namespace dynamics_contact_batch_tests
