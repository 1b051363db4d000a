// Scene files (io/scene.hpp): what a file says is what the world gets, the
// copies of a repeat lie where their rule puts them, a scene loaded from a
// file behaves as physics says (a compound weighs its children's masses
// summed), and every broken file is refused with its file, JSON path and
// expectation while the world stays as it was.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "../world/scenes.hpp"
#include "impulse/io/scene.hpp"

using namespace impulse;

namespace {

// The shared test worlds (tests/world/scenes.hpp), compiled once.
using awake = impulse::test::awake_config;
using awake_double = impulse::test::awake_double_config;
template <class T>
using awake_world = world<std::conditional_t<std::is_same_v<T, float>, awake, awake_double>>;

std::string scenes_dir() { return IMPULSE_SCENES_DIR; }

/// The message of the scene_error that parsing `text` throws ("" if none).
std::string refusal(const std::string& text) {
  try {
    (void)io::parse_scene<float>(text, "broken.json");
  } catch (const io::scene_error& e) {
    CHECK(e.file() == "broken.json");
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE_TEMPLATE("a ball described in a scene file rebounds to 6.58 within 0.25 percent", T, float, double) {
  // The contact solver's bounce scene (tests/world/test_contact_solver.cpp) as
  // a file: radius 0.5 from center height 10, restitution 0.8; it falls 9.5 m
  // to touch and rises 0.8² of that.
  const io::scene<T> scene = io::parse_scene<T>(R"({
    "impulse_scene": 1,
    "bodies": [
      { "type": "static", "shape": { "type": "box", "half_extents": [50, 0.5, 50] }, "position": [0, -0.5, 0] },
      { "name": "ball", "shape": { "type": "sphere", "radius": 0.5 }, "mass": 1,
        "material": { "restitution": 0.8 }, "position": [0, 10, 0] } ] })");
  awake_world<T> w;
  const io::scene_ids ids = io::add_scene(w, scene);
  const body_id ball = ids.body("ball");
  bool rising = false;
  T peak = 0;
  for (int i = 0; i < 600; ++i) {
    w.step(T(1) / 60);
    const T v = w.body(ball).linear_velocity().y, y = w.body(ball).position.y;
    if (v > 0) rising = true;
    if (rising) peak = std::max(peak, y);
    if (rising && v < 0) break;
  }
  constexpr double analytic = 0.5 + 0.64 * 9.5, tolerance = 0.0025;
  CHECK(std::abs(double(peak) / analytic - 1) < tolerance);
}

TEST_CASE("copies repeated along a path with a turn lie on the circle of radius d over 2 sin(theta/2)") {
  const io::scene<double> scene = io::read_scene<double>(scenes_dir() + "/dominoes.json");
  const double d = 0.45, theta = 2.7 * std::numbers::pi / 180, radius = d / (2 * std::sin(theta / 2));
  // The first domino faces +z at the origin; a turn about +y swings +z
  // towards +x, so the arc's center is on its +x side, level with it.
  const std::size_t first = *scene.find_body("domino[0]");
  const vec3<double> start = scene.bodies[first].def.pose.position;
  // Copy 0 steps d along +z before the first turn, so the center lies
  // R·cos(θ/2) to the side of that chord's midpoint, d/2 = R·sin(θ/2) ahead.
  const vec3<double> center = start + vec3<double>{radius * std::cos(theta / 2), 0, radius * std::sin(theta / 2)};
  for (int k = 0; k < 100; ++k) {
    const std::size_t i = *scene.find_body("domino[" + std::to_string(k) + "]");
    const transform<double>& pose = scene.bodies[i].def.pose;
    CHECK(std::abs(length(pose.position - center) - radius) < 1e-9);
    CHECK(std::abs(pose.position.y - 0.5) < 1e-12);
    // Copy k has turned k·θ about y.
    const vec3<double> facing = rotate(pose.rotation, vec3<double>{0, 0, 1});
    CHECK(std::abs(std::atan2(facing.x, facing.z) - std::remainder(k * theta, 2 * std::numbers::pi)) < 1e-9);
  }
  CHECK(!scene.find_body("domino[100]"));
  CHECK(scene.duration == 15);
  CHECK(scene.settings.fixed_dt == doctest::Approx(1.0 / 120));
}

TEST_CASE("a grid of copies is spaced along the first copy's own axes") {
  const io::scene<double> scene = io::parse_scene<double>(R"({
    "impulse_scene": 1,
    "bodies": [ { "name": "b", "shape": { "type": "box", "half_extents": [0.1, 0.1, 0.1] }, "position": [1, 2, 3],
                  "rotation": { "axis": [0, 0, 1], "degrees": 90 },
                  "repeat": { "count": [2, 3, 4], "spacing": [1, 2, 3] } } ] })");
  REQUIRE(scene.bodies.size() == 24);
  // The first copy's x axis points along world +y, its y axis along -x.
  for (std::size_t l = 0; l < 4; ++l)
    for (std::size_t j = 0; j < 3; ++j)
      for (std::size_t i = 0; i < 2; ++i) {
        const std::size_t k = i + 2 * (j + 3 * l);
        const io::scene_body<double>& b = scene.bodies[k];
        CHECK(b.name == "b[" + std::to_string(k) + "]");
        const vec3<double> expected{1.0 - 2.0 * double(j), 2.0 + double(i), 3.0 + 3.0 * double(l)};
        CHECK(length(b.def.pose.position - expected) < 1e-12);
        CHECK(b.shape == scene.bodies[0].shape);  // one shape, shared
      }
}

TEST_CASE("every element of the scene format reads back as the file wrote it") {
  const io::scene<double> s = io::read_scene<double>(scenes_dir() + "/every_element.json");
  const auto body = [&](const char* name) -> const io::scene_body<double>& {
    const auto i = s.find_body(name);
    REQUIRE(i);
    return s.bodies[*i];
  };
  CHECK(s.has_settings);
  CHECK(s.duration == 5);
  CHECK(s.settings.solver.sequential_impulse.velocity_iterations == 20);
  CHECK(s.settings.solver.soft_step.velocity_iterations == 20);
  CHECK(s.settings.solver.sequential_impulse.rest_depth == doctest::Approx(0.000003));
  CHECK(s.settings.solver.soft_step.substeps == 4);
  CHECK(s.settings.solver.soft_step.contact_hertz == 30);
  CHECK(s.settings.solver.sequential_impulse.exact_joint_trees);
  CHECK(s.bodies.size() == 39);
  CHECK(std::holds_alternative<plane<double>>(*body("ground").shape));
  CHECK(std::get<triangle_mesh<double>>(*body("ramp").shape).triangle_count() == 2);
  CHECK(body("ball").def.material.restitution == 0.8);  // rubber
  CHECK(body("ball").def.angular_velocity.z == -4);
  CHECK(body("pill").def.mass == 2);
  CHECK(std::abs(rotate(body("pill").def.pose.rotation, vec3<double>{1, 0, 0}).y - 1) < 1e-12);
  CHECK(!body("wedge").def.awake);
  CHECK(body("wedge").def.material.density == 7800);  // steel
  CHECK(std::get<convex_hull<double>>(*body("wedge").shape).vertex_count() == 6);
  CHECK(body("lift").def.type == body_type::kinematic);
  CHECK(body("bolt").def.bullet);
  CHECK(body("post").def.filter == collision_filter{4, 3, -2});
  CHECK(body("bolt").def.filter == collision_filter{});
  CHECK(body("gate").def.sensor);
  const heightfield<double>& terrain = std::get<heightfield<double>>(*body("terrain").shape);
  CHECK(terrain.columns() == 3);
  CHECK(terrain.spacing_z() == 1.5);
  CHECK(terrain.height(1, 1) == 0.3);
  CHECK(terrain.hole(1, 1));
  CHECK_FALSE(terrain.hole(0, 1));
  CHECK_FALSE(body("post").def.sensor);
  const compound<double>& stool = std::get<compound<double>>(*body("stool").shape);
  REQUIRE(stool.child_count() == 3);
  CHECK(stool.child_at(1).part == compound_part::capsule);
  CHECK(stool.child_at(1).relative_density == 2);
  CHECK(stool.child_at(2).pose.rotation.y == doctest::Approx(std::sin(std::numbers::pi / 8)));
  CHECK(length(body("wall[19]").def.pose.position - vec3<double>{4 * 0.41, 0.1 + 3 * 0.201, -3}) < 1e-12);
  CHECK(length(body("link[3]").def.pose.position - vec3<double>{0.25 + 1.5, 2, 3}) < 1e-12);  // its own -y is world +x

  REQUIRE(s.joints.size() == 8);
  const io::scene_joint<double>& chain2 = s.joints[3];  // "chain[2]": link[2] to link[3]
  CHECK(chain2.name == "chain[2]");
  CHECK(s.bodies[chain2.body_a].name == "link[2]");
  CHECK(s.bodies[chain2.body_b].name == "link[3]");
  CHECK(length(chain2.def.anchor_a - vec3<double>{0.25 + 1.25, 2, 3}) < 1e-12);
  const io::scene_joint<double>& hinge = s.joints[4];
  CHECK(hinge.def.type == joint_type::hinge);
  CHECK(hinge.def.lower == doctest::Approx(-std::numbers::pi / 2));
  CHECK(hinge.def.enable_motor);
  CHECK(hinge.def.max_motor_force == 50);
  const io::scene_joint<double>& slide = s.joints[5];
  CHECK(length(slide.def.anchor_a - vec3<double>{0, 0.5, 3}) < 1e-12);
  CHECK(slide.def.upper == 0.5);
  CHECK(s.joints[6].def.break_force == 500);
  const io::scene_joint<double>& rope = s.joints[7];
  CHECK(rope.def.length == 3.9);
  CHECK(rope.def.spring_hertz == 2);
  CHECK(length(rope.def.anchor_b - vec3<double>{4, 0.5, 3}) < 1e-12);

  REQUIRE(s.particle_systems.size() == 2);
  const io::particle_scene<double>& fountain = *s.find_particles("fountain");
  CHECK(fountain.capacity == 2000);
  CHECK(fountain.wind->variation == 0.4);
  CHECK(fountain.attractors->count == 2);
  CHECK(!fountain.attractors->points[1].enabled);
  CHECK(fountain.planes.size() == 2);
  CHECK(fountain.planes[1].finite);
  CHECK(fountain.emitters[0].random.state == 7);
  CHECK(fountain.initial.size() == 27);
  CHECK(s.find_particles("cloth")->springs->size() == 2);

  // And it loads and runs: 120 steps of every joint, shape and kind.
  world<awake_double> w;
  const io::scene_ids ids = io::add_scene(w, s);
  CHECK(w.body_count() == 39);
  CHECK(w.joint_count() == 8);
  CHECK(ids.joint("rope") == ids.joints[7]);
  for (int i = 0; i < 120; ++i) w.step(1.0 / 60);
  for (const body_id id : ids.bodies) CHECK(is_finite(w.body(id).position));
}

TEST_CASE("each broken scene document is refused naming the JSON path and what was expected") {
  const std::string head = R"({"impulse_scene": 1, )";
  const std::string ball = R"({"shape": {"type": "sphere", "radius": 1}})";
  const struct {
    std::string text, message;
  } cases[] = {
      {"{", "broken.json: (document): not JSON"},
      {"[1e400]", "not JSON"},
      {std::string(40, '[') + std::string(40, ']'), "nested deeper than 32"},
      {"{}", "(document): expected the key \"impulse_scene\""},
      {R"({"impulse_scene": 2})", "/impulse_scene: this reader knows version 1"},
      {head + R"("bodys": []})", "/bodys: unknown key \"bodys\""},
      {head + R"("bodies": {}})", "/bodies: expected an array, got an object"},
      {head + R"("bodies": [{"shape": {"type": "sphere", "radius": -1}}]})",
       "/bodies/0/shape/radius: expected a number > 0, got -1"},
      {head + R"("bodies": [{"shape": {"type": "sphere"}}]})", "/bodies/0/shape: expected the key \"radius\""},
      {head + R"("bodies": [{"shape": {"type": "cone"}}]})", "/bodies/0/shape/type: expected \"sphere\""},
      {head + R"("bodies": [{"shape": {"type": "box", "half_extents": [1, 0, 1]}}]})", "/bodies/0/shape: box"},
      {head + R"("bodies": [{"shape": {"type": "box", "half_extents": [1, 1]}}]})",
       "/bodies/0/shape/half_extents: expected an array of 3 numbers"},
      {head + R"("bodies": [{"shape": {"type": "convex_hull", "vertices": [[0,0,0],[1,0,0],[0,1,0],[1,1,0]]}}]})",
       "/bodies/0/shape/vertices: convex_hull"},
      {head + R"("bodies": [{"shape": {"type": "triangle_mesh", "vertices": [[0,0,0]], "triangles": [[0,0,1]]}}]})",
       "/bodies/0/shape/triangles/0/2: expected a whole number in [0, 0]"},
      {head + R"("bodies": [{"shape": {"type": "plane", "normal": [0, 1, 0]}}]})",
       "/bodies/0/shape: a plane, a triangle mesh or a heightfield has no volume"},
      {head + R"("bodies": [{"shape": "brick"}]})", "/bodies/0/shape: no shape named \"brick\""},
      {head + R"("bodies": [{"shape": {"type": "sphere", "radius": 1e39}}]})",
       "/bodies/0/shape/radius: expected a finite number"},  // past float
      {head + R"("bodies": [{"type": "static", "velocity": [1, 0, 0], "shape": {"type": "sphere", "radius": 1}}]})",
       "/bodies/0: a static body cannot move"},
      {head + R"("bodies": [{"type": "solid", "shape": {"type": "sphere", "radius": 1}}]})",
       "/bodies/0/type: expected \"static\", \"kinematic\" or \"dynamic\""},
      {head + R"("bodies": [{"material": {"restitution": 1.5}, "shape": {"type": "sphere", "radius": 1}}]})",
       "/bodies/0/material/restitution: expected a number in [0, 1], got 1.5"},
      {head + R"("bodies": [{"material": "gold", "shape": {"type": "sphere", "radius": 1}}]})",
       "/bodies/0/material: no material named \"gold\""},
      {head + R"("bodies": [{"rotation": {"axis": [0, 0, 0], "degrees": 9}, "shape": {"type": "sphere", "radius": 1}}]})",
       "/bodies/0/rotation/axis: expected a direction"},
      {head + R"("bodies": [{"rotation": {"quaternion": [0, 0, 0, 0]}, "shape": {"type": "sphere", "radius": 1}}]})",
       "/bodies/0/rotation/quaternion: expected a quaternion of non-zero length"},
      {head + R"("bodies": [{"name": "a", "shape": {"type": "sphere", "radius": 1}}, {"name": "a", "shape": {"type": "sphere", "radius": 1}}]})",
       "/bodies/1/name: a second body named \"a\""},
      {head + R"("bodies": [{"type": "static", "shape": {"type": "heightfield", "columns": 3, "rows": 2, "spacing": [1, 1], "heights": [0, 0, 0, 0, 0]}}]})",
       "/bodies/0/shape/heights: expected columns x rows heights"},
      {head + R"("bodies": [{"type": "static", "shape": {"type": "heightfield", "columns": 3, "rows": 2, "spacing": [1, 1], "heights": [0, 0, 0, 0, 0, 0], "holes": [[2, 0]]}}]})",
       "/bodies/0/shape/holes/0/0: expected a whole number in [0, 1]"},
      {head + R"("bodies": [{"filter": {"group": 3000000000}, "shape": {"type": "sphere", "radius": 1}}]})",
       "/bodies/0/filter/group: expected a whole number in [-2147483647, 2147483647]"},
      {head + R"("bodies": [{"filter": {"mask": -1}, "shape": {"type": "sphere", "radius": 1}}]})",
       "/bodies/0/filter/mask: expected a whole number in [0, 4294967295]"},
      {head + R"("bodies": [{"filter": {"layer": 1}, "shape": {"type": "sphere", "radius": 1}}]})",
       "/bodies/0/filter/layer: unknown key \"layer\""},
      {head + R"("bodies": [{"name": "a", "repeat": {"count": 1000000}, "shape": {"type": "sphere", "radius": 1}}]})",
       "/bodies/0/repeat/count: expected a whole number in [1, 100000]"},
      {head + R"("bodies": [{"name": "a", "repeat": {"count": [2, 2, 1]}, "shape": {"type": "sphere", "radius": 1}}]})",
       "/bodies/0/repeat: expected the key \"spacing\""},
      {head + R"("bodies": [{"name": "a", "repeat": {"count": [1000, 1000, 1], "spacing": [1, 1, 1]}, "shape": {"type": "sphere", "radius": 1}}]})",
       "/bodies/0/repeat/count: more than 100000 copies"},
      {head + R"("bodies": [{"name": "a", "shape": )" + ball.substr(10, ball.size() - 11) + R"(}], "joints": [{"type": "ball", "a": "a", "b": "b", "anchor": [0, 0, 0]}]})",
       "/joints/0/b: no body named \"b\""},
      {head + R"("bodies": [{"name": "a", "repeat": {"count": 2, "step": {"position": [1, 0, 0]}}, "shape": {"type": "sphere", "radius": 0.1}}],
                 "joints": [{"type": "ball", "a": "a[0]", "b": "a[1]", "anchor": [0, 0, 0], "repeat": {"count": 2}}]})",
       "/joints/0/b: copy 1 needs a body named \"a[2]\""},
      {head + R"("bodies": [{"name": "a", "shape": {"type": "sphere", "radius": 1}}, {"name": "b", "shape": {"type": "sphere", "radius": 1}}],
                 "joints": [{"type": "hinge", "a": "a", "b": "b", "anchor": [0, 0, 0]}]})",
       "/joints/0: expected one of \"axis\" or \"axis_on_a\""},
      {head + R"("bodies": [{"name": "a", "shape": {"type": "sphere", "radius": 1}}, {"name": "b", "shape": {"type": "sphere", "radius": 1}}],
                 "joints": [{"type": "hinge", "a": "a", "b": "b", "anchor": [0, 0, 0], "axis": [1, 0, 0], "limits": [1, -1]}]})",
       "/joints/0/limits: expected lower <= upper"},
      {head + R"("bodies": [{"name": "a", "type": "static", "shape": {"type": "sphere", "radius": 1}}, {"name": "b", "type": "static", "shape": {"type": "sphere", "radius": 1}}],
                 "joints": [{"type": "ball", "a": "a", "b": "b", "anchor": [0, 0, 0]}]})",
       "/joints/0: at least one of a joint's bodies must be dynamic"},
      {head + R"("settings": {"time_step": 0}})", "/settings/time_step: expected a number > 0, got 0"},
      {head + R"("settings": {"solver": {"velocity_iteration": 4}}})",
       "/settings/solver/velocity_iteration: unknown solver setting"},
      {head + R"("particles": [{"capacity": 0}]})", "/particles/0/capacity: expected a whole number in [1, 16777216]"},
      {head + R"("particles": [{"capacity": 2, "particles": [{"position": [0, 0, 0], "repeat": {"count": 3, "step": {}}}]}]})",
       "/particles/0/particles/0: more particles than the system's capacity, 2"},
      {head + R"("particles": [{"capacity": 2, "forces": {"springs": [{"a": 0, "b": 1, "rest_length": 1, "stiffness": 1}]}}]})",
       "/particles/0/forces/springs: springs: a spring names a particle that does not exist"},
      {head + R"("particles": [{"capacity": 2, "planes": [{"normal": [0, 1, 0], "friction": 2}]}]})",
       "/particles/0/planes/0/friction: expected a number in [0, 1]"},
      {head + R"("particles": [{"capacity": 2, "emitters": [{"lifetime": 1, "lifetime_spread": 2}]}]})",
       "/particles/0/emitters/0: emitter"},
  };
  for (const auto& c : cases) {
    CAPTURE(c.text);
    const std::string message = refusal(c.text);
    CAPTURE(message);
    CHECK(message.find(c.message) != std::string::npos);
  }
}

TEST_CASE_TEMPLATE("a dynamic compound of two boxes side by side weighs the sum of its children's masses", T, float,
                   double) {
  // Two boxes of 1 × 0.5 × 0.5 m (0.25 m³ each) side by side along x, at
  // 200 kg/m³, the second (named in "shapes", turned about x) at 3 times the
  // density: 50 + 150 = 200 kg, whose center is 0.25 m to the +x side.
  const io::scene<T> scene = io::parse_scene<T>(R"({
    "impulse_scene": 1,
    "shapes": { "heavy": { "type": "box", "half_extents": [0.5, 0.25, 0.25] } },
    "bodies": [
      { "type": "static", "shape": { "type": "box", "half_extents": [50, 0.5, 50] }, "position": [0, -0.5, 0] },
      { "name": "pair", "type": "dynamic", "position": [0, 1, 0], "material": { "density": 200 },
        "shape": { "type": "compound", "children": [
          { "shape": { "type": "box", "half_extents": [0.5, 0.25, 0.25] }, "position": [-0.5, 0, 0] },
          { "shape": "heavy", "position": [0.5, 0, 0], "rotation": { "axis": [1, 0, 0], "degrees": 90 },
            "relative_density": 3 } ] } } ] })",
                                                "pair.json");
  const io::scene_body<T>& pair = scene.bodies[*scene.find_body("pair")];
  CHECK(pair.def.type == body_type::dynamic);
  const compound<T>& shape = std::get<compound<T>>(*pair.shape);
  REQUIRE(shape.child_count() == 2);
  CHECK(shape.child_at(0).relative_density == T(1));
  CHECK(shape.child_at(1).relative_density == T(3));
  CHECK(length(shape.child_at(1).pose.position - vec3<T>{T(0.5), 0, 0}) < T(1e-6));
  CHECK(std::abs(rotate(shape.child_at(1).pose.rotation, vec3<T>{0, 1, 0}).z - 1) < T(1e-6));

  awake_world<T> w;
  const io::scene_ids ids = io::add_scene(w, scene);
  const double density = 200, volume = 8 * 0.5 * 0.25 * 0.25, mass = density * volume + 3 * density * volume;
  CHECK(std::abs(double(w.body(ids.body("pair")).mass) / mass - 1) < 1e-5);
  CHECK(std::abs(double(w.body(ids.body("pair")).position.x) - 0.25) < 1e-5);  // the center of mass
  for (int i = 0; i < 60; ++i) w.step(T(1) / 60);
  CHECK(is_finite(w.body(ids.body("pair")).position));
}

TEST_CASE("a compound's child that is not convex is refused at the child's shape") {
  const std::string head = R"({"impulse_scene": 1, )";
  const std::string brick = R"({"shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5]}})";
  const std::string ball = R"({"type": "sphere", "radius": 1})";
  const std::string inner = R"("inner": {"type": "compound", "children": [)" + brick + "]}";
  // A body whose shape is a compound of `children`, after the shapes `named`.
  const auto body = [&](const std::string& children, const std::string& named = "") {
    return head + (named.empty() ? "" : R"("shapes": {)" + named + "}, ") +
           R"("bodies": [{"shape": {"type": "compound", "children": [)" + children + "]}}]}";
  };
  const std::string child = "/bodies/0/shape/children/";
  const struct {
    std::string text, path, message;
  } cases[] = {
      {body(brick + R"(, {"shape": {"type": "plane", "normal": [0, 1, 0]}})"), child + "1/shape",
       "a compound's child must be a sphere, a box, a capsule or a convex_hull, not a plane"},
      {body(R"({"shape": {"type": "compound", "children": [)" + brick + "]}}"), child + "0/shape", "not a compound"},
      // Refused by its type before it is read: not for its missing vertices.
      {body(R"({"shape": {"type": "triangle_mesh"}})"), child + "0/shape", "not a triangle_mesh"},
      {body(R"({"shape": {"type": "heightfield"}})"), child + "0/shape", "not a heightfield"},
      {body(brick + R"(, {"shape": "floor"})", R"("floor": {"type": "plane", "normal": [0, 1, 0]})"), child + "1/shape",
       "not a plane"},
      {body(R"({"shape": "inner", "position": [1, 0, 0]})", inner), child + "0/shape", "not a compound"},
      {head + R"("shapes": {"outer": {"type": "compound", "children": [{"shape": "inner"}]}, )" + inner + "}}",
       "/shapes/outer/children/0/shape", "not a compound"},
      {body(R"({"position": [0, 0, 0]})"), child + "0", "expected the key \"shape\""},
      {body(R"({"shape": "brick"})"), child + "0/shape", "no shape named \"brick\""},
      {body(""), "/bodies/0/shape/children", "expected an array of at least 1"},
      {body(R"({"shape": )" + ball + R"(, "relative_density": 0})"), child + "0/relative_density",
       "expected a number > 0, got 0"},
      {body(R"({"shape": )" + ball + R"(, "density": 2})"), child + "0/density", "unknown key \"density\""},
      {body(R"({"shape": )" + ball + R"(, "rotation": {"axis": [0, 0, 0], "degrees": 9}})"), child + "0/rotation/axis",
       "expected a direction"},
      {head + R"("bodies": [{"shape": {"type": "cone"}}]})", "/bodies/0/shape/type",
       "\"triangle_mesh\", \"heightfield\" or \"compound\", got \"cone\""},
  };
  for (const auto& c : cases) {
    CAPTURE(c.text);
    const std::string message = refusal(c.text);
    CAPTURE(message);
    CHECK(message.find("broken.json: " + c.path + ": ") == 0);
    CHECK(message.find(c.message) != std::string::npos);
  }
  // A compound under "shapes" may name a shape whose key sorts after its own.
  const io::scene<float> named = io::parse_scene<float>(head + R"(
    "shapes": { "a": { "type": "compound", "children": [{ "shape": "b" }, { "shape": "b", "position": [1, 0, 0] }] },
                "b": { "type": "sphere", "radius": 0.5 } },
    "bodies": [{ "shape": "a" }] })");
  CHECK(std::get<compound<float>>(*named.bodies[0].shape).child_count() == 2);
}

TEST_CASE("a scene's solver numbers reach the world of either solver: the shared ones both, each solver's own its own") {
  const io::scene<float> scene = io::parse_scene<float>(R"({
    "impulse_scene": 1,
    "settings": { "solver": { "velocity_iterations": 7, "substeps": 8, "rest_depth": 0.00001 } },
    "bodies": [] })",
                                                         "solver.json");
  world<awake> sequential;
  (void)io::add_scene(sequential, scene);
  CHECK(sequential.settings().solver.velocity_iterations == 7);
  CHECK(sequential.settings().solver.rest_depth == doctest::Approx(0.00001f));
  CHECK(sequential.settings().solver.substeps == 8);  // both solvers have substeps
  world<impulse::test::soft_config> substepping;
  (void)io::add_scene(substepping, scene);
  CHECK(substepping.settings().solver.velocity_iterations == 7);
  CHECK(substepping.settings().solver.substeps == 8);
}

TEST_CASE("a scene the world refuses leaves the world as it was") {
  world<awake> w;
  const body_id resident = w.create_body({}, sphere<float>::make(0.5f));
  // Both bodies are valid scene values, but the second one's mass,
  // 3e38 kg/m³ times 8 m³, is past float: create_body refuses it.
  const io::scene<float> heavy = io::parse_scene<float>(R"({
    "impulse_scene": 1,
    "settings": { "gravity": [0, -1, 0] },
    "bodies": [ { "name": "fine", "shape": { "type": "sphere", "radius": 1 }, "position": [5, 0, 0] },
                { "name": "heavy", "shape": { "type": "box", "half_extents": [1, 1, 1] }, "position": [9, 0, 0],
                  "material": { "density": 3e38 } } ] })",
                                                         "heavy.json");
  try {
    (void)io::add_scene(w, heavy);
    FAIL("the heavy body was accepted");
  } catch (const io::scene_error& e) {
    CHECK(std::string(e.what()).find("heavy.json: /bodies/1: ") == 0);
  }
  CHECK(w.body_count() == 1);
  CHECK(w.contains(resident));
  CHECK(w.settings().gravity.y == doctest::Approx(-9.81f));  // the file's settings were not applied

  // A shape the config does not compile is refused before anything changes.
  struct spheres_only : awake {
    using shapes = shape_list<sphere>;
  };
  world<spheres_only> small;
  const io::scene<float> hull = io::parse_scene<float>(R"({
    "impulse_scene": 1,
    "bodies": [ { "shape": { "type": "sphere", "radius": 1 } },
                { "shape": { "type": "convex_hull", "vertices": [[0,0,0],[1,0,0],[0,1,0],[0,0,1]] } } ] })",
                                                       "hull.json");
  try {
    (void)io::add_scene(small, hull);
    FAIL("the hull was accepted");
  } catch (const io::scene_error& e) {
    CHECK(std::string(e.what()).find("hull.json: /bodies/1/shape: this world's config does not compile") == 0);
  }
  CHECK(small.body_count() == 0);
}

TEST_CASE("a particle scene sets the forces planes emitters and particles of a system") {
  const io::scene<float> s = io::read_scene<float>(scenes_dir() + "/every_element.json");
  const io::particle_scene<float>& fountain = *s.find_particles("fountain");
  using full = particles::particle_system<default_config, particles::gravity, particles::drag, particles::wind,
                                          particles::point_forces>;
  full system = io::make_particles<full>(fountain);
  CHECK(system.capacity() == 2000);
  CHECK(system.size() == 27);
  CHECK(system.force<particles::drag>().coefficient == 0.05f);
  CHECK(system.force<particles::wind>().velocity.x == 2.0f);
  CHECK(system.force<particles::point_forces>().points[0].strength == 20.0f);
  CHECK(system.planes().size() == 2);
  CHECK(system.emitters().size() == 1);
  CHECK(system.lifetime(0) == 10.0f);

  // A system whose force list lacks wind takes none of it.
  using no_wind = particles::particle_system<default_config, particles::gravity, particles::drag,
                                             particles::point_forces>;
  no_wind other(100);
  try {
    io::add_particles(other, fountain, "every_element.json");
    FAIL("wind was accepted");
  } catch (const io::scene_error& e) {
    CHECK(std::string(e.what()) ==
          "every_element.json: /particles/0/forces/wind: this particle_system's force list has no wind");
  }
  CHECK(other.size() == 0);
  CHECK(other.planes().empty());
  CHECK(other.force<particles::drag>().coefficient == 0.1f);

  // The cloth's springs hold its three particles: they hang, and stay finite.
  const io::particle_scene<float>& cloth = *s.find_particles("cloth");
  using sprung = particles::particle_system<default_config, particles::gravity, particles::springs>;
  sprung strand = io::make_particles<sprung>(cloth);
  CHECK(strand.size() == 3);
  CHECK(strand.force<particles::springs>().size() == 2);
}

TEST_CASE("the 100 dominoes of dominoes.json topple one after another at a steady pace to the last") {
  // A domino has toppled when its long axis leans 45° from the vertical.
  // Once under way the wave runs at a speed set by the spacing and the
  // height alone, so the time between neighbours settles.
  const io::scene<float> scene = io::read_scene<float>(scenes_dir() + "/dominoes.json");
  world<default_config> w;
  const io::scene_ids ids = io::add_scene(w, scene);
  std::vector<body_id> dominoes;
  for (int k = 0; k < 100; ++k) dominoes.push_back(ids.body("domino[" + std::to_string(k) + "]"));
  std::vector<float> toppled(100, -1);
  const int steps = int(std::lround(scene.duration / scene.settings.fixed_dt));
  for (int i = 0; i < steps; ++i) {
    w.step(scene.settings.fixed_dt);
    for (std::size_t k = 0; k < 100; ++k)
      if (toppled[k] < 0 && rotate(w.body(dominoes[k]).orientation, vec3<float>{0, 1, 0}).y < std::sqrt(0.5f))
        toppled[k] = w.time();
  }
  for (std::size_t k = 0; k < 100; ++k) {
    CAPTURE(k);
    CHECK(toppled[k] > 0);
    if (k > 0) CHECK(toppled[k] > toppled[k - 1]);
  }
  // The wave's speed is steady from the tenth domino to the third from
  // last: every span of ten dominoes takes within 5 % of the median span
  // (about 1.2 s). A single interval is only known to a step (1/120 s of
  // 0.12 s, 7 %), and compilers' rounding moves one by a step or two; over
  // ten of them a step is 0.7 %. The last two fall sooner, with no
  // neighbour ahead to push over.
  std::vector<float> spans;
  for (std::size_t k = 10; k + 10 <= 97; ++k) spans.push_back(toppled[k + 10] - toppled[k]);
  std::vector<float> sorted = spans;
  std::sort(sorted.begin(), sorted.end());
  const float median = sorted[sorted.size() / 2];
  CHECK(median > 0);
  for (const float span : spans) CHECK(std::abs(span / median - 1) < 0.05f);
  CHECK(toppled[99] - toppled[98] < median / 10);
}

namespace {

/// When each stage of rube_goldberg.json happened (s; -1: never), and
/// whether the ball is in the cup at the end, at rest.
struct machine_run {
  double lever = -1, first_domino = -1, last_domino = -1, weld = -1, seesaw = -1, cup = -1;
  bool rests_in_cup = false;
};

template <class Config>
machine_run run_machine() {
  using T = typename Config::scalar;
  const io::scene<T> scene = io::read_scene<T>(scenes_dir() + "/rube_goldberg.json");
  world<Config> w;
  const io::scene_ids ids = io::add_scene(w, scene);
  // The cup's inside, from its walls: x between cup_wall[0] and [1], z
  // between cup_side[0] and [1], below the walls' top.
  const auto inner = [&](const char* name, int side) {
    const io::scene_body<T>& b = scene.bodies[*scene.find_body(name)];
    return b.def.pose.position + std::get<box<T>>(*b.shape).half_extents * T(side);
  };
  const vec3<T> low{inner("cup_wall[0]", 1).x, 0, inner("cup_side[0]", 1).z};
  const vec3<T> high{inner("cup_wall[1]", -1).x, inner("cup_wall[0]", 1).y, inner("cup_side[1]", -1).z};
  const auto in_cup = [&](const vec3<T>& p) {
    return p.x > low.x && p.x < high.x && p.z > low.z && p.z < high.z && p.y < high.y;
  };
  const body_id ball = ids.body("projectile");
  machine_run run;
  const auto mark = [&](double& when, bool happened) {
    if (when < 0 && happened) when = double(w.time());
  };
  const T dt = scene.settings.fixed_dt;
  for (int i = 0; i < int(std::lround(scene.duration / dt)); ++i) {
    w.step(dt);
    mark(run.lever, std::abs(w.joint_position(ids.joint("lever_hinge"))) > T(0.1));
    mark(run.first_domino, rotate(w.body(ids.body("domino[0]")).orientation, vec3<T>{0, 1, 0}).y < T(0.7071));
    mark(run.last_domino, rotate(w.body(ids.body("domino[7]")).orientation, vec3<T>{0, 1, 0}).y < T(0.7071));
    mark(run.weld, w.is_broken(ids.joint("shelf_weld")));
    mark(run.seesaw, w.joint_position(ids.joint("seesaw_hinge")) > T(0.1));
    mark(run.cup, in_cup(w.body(ball).position));
  }
  run.rests_in_cup = in_cup(w.body(ball).position) && length(w.body(ball).linear_velocity()) < T(0.05);
  return run;
}

struct machine_float : default_config {
  static constexpr bool ccd = true;
};
struct machine_double : machine_float {
  using scalar = double;
};
struct machine_soft_step : machine_float {
  using solver = solver::soft_step;
};

}  // namespace

TEST_CASE_TEMPLATE("the rube goldberg machine runs its stages in order and the ball ends at rest in the cup", C,
                   machine_float, machine_double, machine_soft_step) {
  // Each stage can only start once the one before it has: the ball reaches
  // the lever, the lever the first domino, the last domino the shelf, whose
  // weld breaks and drops the block on the seesaw, which throws the ball.
  const machine_run run = run_machine<C>();
  CHECK(run.lever > 0);
  CHECK(run.first_domino > run.lever);
  CHECK(run.last_domino > run.first_domino);
  CHECK(run.weld >= run.last_domino);
  CHECK(run.seesaw > run.weld);
  CHECK(run.cup > run.seesaw);
  CHECK(run.rests_in_cup);
}

TEST_CASE("a newtons cradle passes the first ball's energy down the row to the last") {
  // The first ball falls h = 1 - cos 40° = 0.234 m and strikes the row a
  // quarter period (0.5 s) later. Elastic (e = 1) and 1 mm apart, the
  // impacts pass its momentum ball by ball: the last ball rises to h, less
  // what the contacts lose (1.2 % here), while the middle three and the
  // first stay where they are.
  const io::scene<double> scene = io::read_scene<double>(scenes_dir() + "/newtons_cradle.json");
  // One repeated joint hangs the four balls: the beam (no brackets) in every
  // copy, the anchor stepped 0.201 m along x each time.
  REQUIRE(scene.joints.size() == 5);
  for (std::size_t k = 0; k < 4; ++k) {
    const io::scene_joint<double>& rod = scene.joints[1 + k];
    CHECK(rod.name == "rod[" + std::to_string(k) + "]");
    CHECK(scene.bodies[rod.body_a].name == "beam");
    CHECK(scene.bodies[rod.body_b].name == "ball[" + std::to_string(k) + "]");
    CHECK(length(rod.def.anchor_a - vec3<double>{0.201 * double(k + 1), 1.5, 0}) < 1e-12);
  }
  world<awake_double> w;
  const io::scene_ids ids = io::add_scene(w, scene);
  const body_id first = ids.body("striker"), last = ids.body("ball[3]");
  const double rest = w.body(last).position.y, drop = w.body(first).position.y - rest;
  CHECK(drop == doctest::Approx(1 - std::cos(40 * std::numbers::pi / 180)));
  double last_rise = 0, first_after = 0, middle = 0;
  for (int i = 0; i < int(std::lround(1.5 / scene.settings.fixed_dt)); ++i) {
    w.step(scene.settings.fixed_dt);
    last_rise = std::max(last_rise, w.body(last).position.y - rest);
    if (w.time() > 0.6) first_after = std::max(first_after, w.body(first).position.y - rest);
    for (const char* name : {"ball[0]", "ball[1]", "ball[2]"})
      middle = std::max(middle, std::abs(w.body(ids.body(name)).position.y - rest));
  }
  CHECK(last_rise / drop > 0.97);
  CHECK(last_rise / drop < 1.0);  // never more energy than it was given
  CHECK(first_after / drop < 0.01);
  CHECK(middle < 1e-4);
}

TEST_CASE("the tower and the pyramid of stacking.json stand within 1 mm and sleep within 1 s") {
  const io::scene<float> scene = io::read_scene<float>(scenes_dir() + "/stacking.json");
  world<default_config> w;
  const io::scene_ids ids = io::add_scene(w, scene);
  REQUIRE(ids.bodies.size() == 1 + 12 + 36);
  std::vector<vec3<float>> placed;
  for (const body_id id : ids.bodies) placed.push_back(w.body(id).position);
  float drift = 0, asleep = -1;
  for (int i = 0; i < int(std::lround(scene.duration / scene.settings.fixed_dt)); ++i) {
    w.step(scene.settings.fixed_dt);
    for (std::size_t k = 0; k < placed.size(); ++k) drift = std::max(drift, length(w.body(ids.bodies[k]).position - placed[k]));
    if (asleep < 0 && w.awake_body_count() == 0) asleep = w.time();
  }
  CHECK(drift < 0.001f);
  CHECK(asleep > 0);
  CHECK(asleep < 1.0f);
}
