// Heightfields: the grid's triangles and active edges, bad grids refused,
// and the narrow phase and ray casts equal to those of the triangle mesh
// with the same triangles; in a world, a box slides over a many-celled
// flat field as over a plane, and a ball falls through a hole.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "../error_code_of.hpp"
#include "../world/scenes.hpp"
#include "impulse/core/random.hpp"
#include "impulse/narrowphase.hpp"
#include "impulse/shapes.hpp"
#include "impulse/world.hpp"

namespace shapes_heightfield_tests {

using namespace impulse;
using impulse::test::error_code_of;

namespace {

/// A 9 × 7 grid at 0.5 × 0.75 m of gentle bumps, a ridge along x = 2 and a
/// hole at cell (5, 3).
heightfield<double> bumpy(bool with_hole = true) {
  const std::size_t nx = 9, nz = 7;
  std::vector<double> h(nx * nz);
  for (std::size_t k = 0; k < nz; ++k)
    for (std::size_t i = 0; i < nx; ++i)
      h[k * nx + i] = 0.1 * std::sin(double(i)) * std::cos(0.7 * double(k)) + (i == 4 ? 0.3 : 0.0);
  std::vector<std::uint8_t> holes((nx - 1) * (nz - 1), 0);
  if (with_hole) holes[3 * (nx - 1) + 5] = 1;
  return heightfield<double>::make(nx, nz, 0.5, 0.75, h, holes);
}

/// The triangle mesh of the same triangles, in the same order, holes left out.
triangle_mesh<double> as_mesh(const heightfield<double>& f) {
  std::vector<vec3<double>> points;
  std::vector<std::uint32_t> indices;
  for (std::size_t t = 0; t < f.triangle_count(); ++t) {
    const std::size_t cell = t / 2;
    if (f.hole(cell % (f.columns() - 1), cell / (f.columns() - 1))) continue;
    vec3<double> a, b, c;
    f.triangle(t, a, b, c);
    for (const vec3<double>& p : {a, b, c}) {
      indices.push_back(std::uint32_t(points.size()));
      points.push_back(p);
    }
  }
  return triangle_mesh<double>::make(points, indices);
}

}  // namespace

TEST_CASE("a heightfield's triangles face up, and its active edges are the mesh's of the same triangles") {
  const heightfield<double> f = bumpy();
  const triangle_mesh<double> m = as_mesh(f);
  std::size_t mesh_t = 0, internal = 0, active = 0;
  for (std::size_t t = 0; t < f.triangle_count(); ++t) {
    const std::size_t cell = t / 2;
    if (f.hole(cell % 8, cell / 8)) continue;
    vec3<double> a, b, c;
    f.triangle(t, a, b, c);
    CHECK(cross(b - a, c - a).y > 0);  // counter-clockwise from above
    CAPTURE(t);
    CHECK(f.active_edges(t) == m.active_edges(mesh_t));
    for (const std::uint8_t bit : {heightfield<double>::edge_ab, heightfield<double>::edge_bc, heightfield<double>::edge_ca})
      ((f.active_edges(t) & bit) ? active : internal) += 1;
    ++mesh_t;
  }
  CHECK(mesh_t == m.triangle_count());
  // Both kinds occur: the border, the hole's rim and the ridge are active,
  // the gentle bumps' seams internal.
  CHECK(internal > 100);
  CHECK(active > 30);
}

TEST_CASE("a heightfield refuses grids it cannot stand for") {
  const std::vector<double> four{0, 0, 0, 0};
  CHECK(error_code_of([&] { (void)heightfield<double>::make(1, 4, 1, 1, four); }) == error_code::degenerate_shape);
  CHECK(error_code_of([&] { (void)heightfield<double>::make(2, 2, 0, 1, four); }) == error_code::invalid_parameter);
  CHECK(error_code_of([&] { (void)heightfield<double>::make(3, 2, 1, 1, four); }) == error_code::invalid_parameter);
  const std::vector<double> bad{0, std::nan(""), 0, 0};
  CHECK(error_code_of([&] { (void)heightfield<double>::make(2, 2, 1, 1, bad); }) == error_code::non_finite);
  const std::vector<std::uint8_t> holes{0, 0};
  CHECK(error_code_of([&] { (void)heightfield<double>::make(2, 2, 1, 1, four, holes); }) == error_code::invalid_parameter);
  CHECK(error_code_of([&] { heightfield<double>{}.validate(); }) == error_code::degenerate_shape);
}

TEST_CASE("a heightfield's contacts and ray hits are the mesh's of the same triangles") {
  const heightfield<double> f = bumpy();
  const triangle_mesh<double> m = as_mesh(f);
  const transform<double> at{{-1, 0.5, 2}, quat<double>::from_axis_angle({0, 1, 0}, 0.3)};
  lcg32 random{5};
  const auto uniform = [&](double lo, double hi) { return random.uniform<double>(lo, hi); };
  int touching = 0;
  const auto compare = [&](const auto& shape) {
    for (int n = 0; n < 300; ++n) {
      // Somewhere over the field, low enough to touch it often.
      const vec3<double> local{uniform(0, 4), uniform(-0.3, 0.6), uniform(0, 4.5)};
      const transform<double> pose{apply(at, local), normalize(quat<double>{uniform(-1, 1), uniform(-1, 1),
                                                                            uniform(-1, 1), uniform(0.1, 1)})};
      std::array<contact_manifold<double>, 4> from_field, from_mesh;
      const std::size_t a = narrowphase::collide(f, at, shape, pose, 0.01, std::span<contact_manifold<double>>(from_field));
      const std::size_t b = narrowphase::collide(m, at, shape, pose, 0.01, std::span<contact_manifold<double>>(from_mesh));
      REQUIRE((a > 0) == (b > 0));
      touching += a > 0;
      // The triangles come in another order (the grid's rows, the mesh's
      // tree), and merging groups manifolds whose normals are within its
      // cone (cosine 0.999) greedily in that order: the groups can differ
      // (one manifold here, two there) but not what touches. The deepest
      // point is the same to the bit, and every normal of one has one of
      // the other within twice the cone.
      const auto deepest = [](std::span<const contact_manifold<double>> ms) {
        double most = -1e300;
        for (const contact_manifold<double>& m : ms)
          for (const contact_point<double>& p : m.contacts()) most = std::max(most, p.depth);
        return most;
      };
      const std::span<const contact_manifold<double>> x(from_field.data(), a), y(from_mesh.data(), b);
      CHECK(std::abs(deepest(x) - deepest(y)) < 1e-9);
      const auto near = [](const contact_manifold<double>& m, std::span<const contact_manifold<double>> others) {
        return std::ranges::any_of(others, [&](const contact_manifold<double>& o) { return dot(o.normal, m.normal) > 0.996; });
      };
      for (const contact_manifold<double>& m : x) CHECK(near(m, y));
      for (const contact_manifold<double>& m : y) CHECK(near(m, x));
    }
  };
  compare(sphere<double>::make(0.3));
  compare(capsule<double>::make(0.2, 0.4));
  compare(box<double>::make({0.4, 0.2, 0.3}));
  const std::vector<vec3<double>> points{{0, 0, 0}, {0.5, 0, 0}, {0, 0.4, 0}, {0, 0, 0.3}, {0.3, 0.3, 0.3}};
  compare(convex_hull<double>::from_points(points));
  CHECK(touching > 300);
  // Rays from above at random: the same hits, the hole's included.
  int hits = 0;
  for (int n = 0; n < 500; ++n) {
    const ray<double> r{apply(at, vec3<double>{uniform(-0.5, 4.5), 2, uniform(-0.5, 5)}),
                        rotate(at.rotation, vec3<double>{uniform(-1, 1), -3, uniform(-1, 1)})};
    const narrowphase::ray_hit<double> x = narrowphase::ray_cast(r, f, at), y = narrowphase::ray_cast(r, m, at);
    REQUIRE(bool(x) == bool(y));
    if (!x) continue;
    ++hits;
    CHECK(std::abs(x.fraction - y.fraction) < 1e-12);
    CHECK(length(x.normal - y.normal) < 1e-12);
  }
  CHECK(hits > 300);
}

TEST_CASE("a box slides over a flat heightfield of many cells as over a plane, and a ball falls through a hole") {
  // A 41 × 41 field of 0.25 m cells, flat at y = 0, with a hole at the
  // cell under (7.1, 5.1). The box starts at 4 m/s along x with friction
  // 0.6 on both: it stops after v²/(2μg) = 1.359 m, catching on no seam.
  const std::size_t n = 41;
  std::vector<float> flat(n * n, 0.0f);
  std::vector<std::uint8_t> holes((n - 1) * (n - 1), 0);
  holes[20 * (n - 1) + 28] = 1;
  impulse::test::with_sleeping_off_and_on([&](auto& w) {
    body_def<float> d;
    d.type = body_type::static_body;
    d.material.friction = 0.6f;
    w.create_body(d, heightfield<float>::make(n, n, 0.25f, 0.25f, flat, holes));
    const body_id cube = impulse::test::add_cube(w, {1, 0.5f, 3});
    impulse::test::run(w, 10);
    const float x0 = w.body(cube).position.x;
    w.set_velocity(cube, {4, 0, 0}, {});
    impulse::test::run(w, 120);
    CHECK(w.body(cube).position.x - x0 == doctest::Approx(16.0f / (2 * 0.6f * 9.81f)).epsilon(0.02));
    CHECK(std::abs(w.body(cube).position.y - 0.5f) < 0.01f);
    CHECK(length(w.body(cube).angular_velocity()) < 0.01f);
    // A ray down through the hole (x 7 to 7.25, z 5 to 5.25) finds
    // nothing; one beside it the surface.
    CHECK_FALSE(w.ray_cast(ray<float>{{7.125f, 1, 5.125f}, {0, -2, 0}}));
    const auto ground = w.ray_cast(ray<float>{{6.5f, 1, 5.125f}, {0, -2, 0}});
    REQUIRE(ground);
    CHECK(ground->fraction == doctest::Approx(0.5f).epsilon(1e-5));
    // A ball of radius 0.1 dropped over the hole falls through.
    body_def<float> b;
    b.pose.position = {7.125f, 1, 5.125f};
    const body_id ball = w.create_body(b, sphere<float>::make(0.1f));
    impulse::test::run(w, 60);
    CHECK(w.body(ball).position.y < -1);
  });
}

TEST_CASE("a dynamic heightfield is refused, the world unchanged") {
  world<impulse::test::awake_config> w;
  const std::vector<float> flat(4, 0.0f);
  body_def<float> d;
  CHECK(error_code_of([&] { w.create_body(d, heightfield<float>::make(2, 2, 1, 1, flat)); }) ==
        error_code::invalid_parameter);
  CHECK(w.body_count() == 0);
}

}  // namespace shapes_heightfield_tests
