// Debug drawing of shapes and joints: each shape's wireframe lies on the
// shape's surface where it is, in its body's colour, and each joint's
// anchors, axis and limits are drawn where the joint has them.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "impulse/world.hpp"
#include "scenes.hpp"

namespace world_debug_draw_tests {

using namespace impulse;
using world_type = world<impulse::test::awake_config>;

namespace {

struct segment {
  vec3<float> a, b;
  debug_color color;
};

/// Keeps everything drawn.
struct recorder {
  std::vector<segment> lines, arrows;
  std::vector<vec3<float>> points;
  void line(const vec3<float>& a, const vec3<float>& b, const debug_color& c) { lines.push_back({a, b, c}); }
  void point(const vec3<float>& p, const debug_color&) { points.push_back(p); }
  void arrow(const vec3<float>& a, const vec3<float>& b, const debug_color& c) { arrows.push_back({a, b, c}); }
};

world_settings<float> weightless() {
  world_settings<float> s;
  s.gravity = {0, 0, 0};
  return s;
}

debug_draw_flags only(bool shapes, bool joints) {
  debug_draw_flags f;
  f.shapes = shapes;
  f.joints = joints;
  f.contacts = f.normals = false;
  return f;
}

}  // namespace

TEST_CASE("each shape's wireframe lies on its surface where the body is") {
  const quat<float> turn = quat<float>::from_axis_angle(normalize(vec3<float>{1, 2, 3}), 0.7f);
  const vec3<float> at{3, -2, 5};
  const auto drawn = [&](const auto& shape) {
    world_type w(weightless());
    body_def<float> d;
    d.pose = {at, turn};
    w.create_body(d, shape);
    recorder r;
    w.draw(r, only(true, false));
    return r;
  };
  SUBCASE("a sphere: three great circles of 16 segments, every end a radius from the center") {
    const recorder r = drawn(sphere<float>::make(0.7f));
    CHECK(r.lines.size() == 48);
    for (const segment& s : r.lines) {
      CHECK(std::abs(length(s.a - at) - 0.7f) < 1e-5f);
      CHECK(std::abs(length(s.b - at) - 0.7f) < 1e-5f);
    }
  }
  SUBCASE("a box: its 12 edges, between its turned corners") {
    const vec3<float> half{0.5f, 1, 1.5f};
    const recorder r = drawn(box<float>::make(half));
    CHECK(r.lines.size() == 12);
    float total = 0;
    for (const segment& s : r.lines) {
      total += length(s.b - s.a);
      const vec3<float> local = inverse_rotate(turn, s.a - at);
      CHECK(std::abs(std::abs(local.x) - half.x) < 1e-5f);
      CHECK(std::abs(std::abs(local.y) - half.y) < 1e-5f);
      CHECK(std::abs(std::abs(local.z) - half.z) < 1e-5f);
    }
    CHECK(total == doctest::Approx(8 * (half.x + half.y + half.z)).epsilon(1e-5));  // 4 edges of each length
  }
  SUBCASE("a capsule: every end a radius from its core segment") {
    const recorder r = drawn(capsule<float>::make(0.3f, 0.8f));
    CHECK(r.lines.size() == 2 * 16 + 4 + 4 * 8);
    const vec3<float> axis = rotate(turn, vec3<float>{0, 1, 0});
    const auto from_core = [&](const vec3<float>& p) {
      const float along = std::clamp(dot(p - at, axis), -0.8f, 0.8f);
      return length(p - (at + axis * along));
    };
    for (const segment& s : r.lines) {
      CHECK(std::abs(from_core(s.a) - 0.3f) < 1e-5f);
      CHECK(std::abs(from_core(s.b) - 0.3f) < 1e-5f);
    }
  }
  SUBCASE("a hull: its edges, V + F − 2 of them") {
    const std::vector<vec3<float>> points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    const convex_hull<float> h = convex_hull<float>::from_points(points);
    const recorder r = drawn(h);
    CHECK(r.lines.size() == h.vertex_count() + h.face_count() - 2);
  }
}

TEST_CASE("a static mesh, a plane and a sensor are drawn in their colours") {
  world_type w(weightless());
  const vec3<float> corners[] = {{-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}};
  const std::uint32_t triangles[] = {0, 1, 2, 0, 2, 3};
  body_def<float> d;
  d.type = body_type::static_body;
  w.create_body(d, triangle_mesh<float>::make(corners, triangles));
  d.pose.position = {0, -3, 0};
  w.create_body(d, plane<float>::make({0, 1, 0}, 0));
  d.sensor = true;
  d.pose.position = {0, 5, 0};
  w.create_body(d, box<float>::make({1, 1, 1}));
  recorder r;
  w.draw(r, only(true, false));
  CHECK(r.lines.size() == 6 + 4 + 12);  // the mesh's two triangles, the plane's square, the sensor's box
  CHECK(r.arrows.size() == 1);          // the plane's normal, from its surface
  CHECK(length(r.arrows[0].a - vec3<float>{0, -3, 0}) < 1e-6f);
  CHECK(length(r.arrows[0].b - vec3<float>{0, -2, 0}) < 1e-6f);
  int yellow = 0;
  for (const segment& s : r.lines) yellow += s.color.r == 1 && s.color.g > 0.8f && s.color.b < 0.3f;
  CHECK(yellow == 12);
}

TEST_CASE("a heightfield is drawn as its triangles, less its holes") {
  world_type w(weightless());
  const std::vector<float> heights(16, 0.5f);
  std::vector<std::uint8_t> holes(9, 0);
  holes[4] = 1;  // the middle cell
  body_def<float> d;
  d.type = body_type::static_body;
  d.pose.position = {-1, 0, -1};
  w.create_body(d, heightfield<float>::make(4, 4, 1, 1, heights, holes));
  recorder r;
  w.draw(r, only(true, false));
  CHECK(r.lines.size() == 8 * 2 * 3);  // 8 cells of two triangles
  for (const segment& s : r.lines) {
    CHECK(s.a.y == 0.5f);
    CHECK(s.a.x >= -1);
    CHECK(s.a.x <= 2);
  }
}

TEST_CASE("a joint is drawn at its anchors, with a hinge's axis and the arc of its limits") {
  world_type w(weightless());
  body_def<float> d;
  d.type = body_type::static_body;
  const body_id frame = w.create_body(d, box<float>::make({0.1f, 0.1f, 0.1f}));
  d.type = body_type::dynamic;
  d.pose.position = {1, 0, 0};
  const body_id door = w.create_body(d, box<float>::make({0.5f, 1, 0.05f}));
  joint_def<float> hinge = joint_def<float>::hinge(frame, door, {0.5f, 0, 0}, {0, 1, 0});
  hinge.enable_limit = true;
  hinge.lower = -0.5f;
  hinge.upper = 1.0f;
  w.create_joint(hinge);
  recorder r;
  w.draw(r, only(false, true));
  // Both anchors at the hinge point, a lever line from each body's center.
  REQUIRE(r.points.size() == 2);
  for (const vec3<float>& p : r.points) CHECK(length(p - vec3<float>{0.5f, 0, 0}) < 1e-5f);
  REQUIRE(r.arrows.size() == 1);
  CHECK(length(r.arrows[0].b - r.arrows[0].a - vec3<float>{0, 0.3f, 0}) < 1e-5f);
  // The limits' arc: 1.5 rad in ceil(1.5/2π·16) = 4 segments, 0.2 m out.
  CHECK(r.lines.size() == 2 + 4);
  float swept = 0;
  for (std::size_t k = 2; k < r.lines.size(); ++k) {
    const segment& s = r.lines[k];
    CHECK(std::abs(length(s.a - vec3<float>{0.5f, 0, 0}) - 0.2f) < 1e-5f);
    CHECK(std::abs(s.a.y) < 1e-6f);
    swept += 2 * std::asin(length(s.b - s.a) / 0.4f);
  }
  CHECK(swept == doctest::Approx(1.5f).epsilon(1e-4));
}

}  // namespace world_debug_draw_tests
