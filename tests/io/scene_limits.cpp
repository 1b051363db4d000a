// Scene files cannot ask for unbounded memory (io/scene.hpp, scene_limits):
// the limits hold over the whole document (bodies, joints, particles summed
// over all systems, vertices and triangles summed over all meshes and hulls,
// children summed over all compounds, bytes, JSON values and nesting), each
// is checked before the memory it guards is allocated, and each refusal is
// a scene_error with error_code::capacity_exceeded naming the JSON path of
// the value that crossed it. A key given twice in one object is refused
// with its path, and particle masses too small to invert and emitter rates
// past max_rate are refused where the file gives them.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "impulse/io/scene.hpp"

using namespace impulse;

namespace {

/// What parsing `text` under `limits` refused: the error's path, message
/// and code; `refused` is false if the scene loaded.
struct refusal {
  bool refused = false;
  std::string path, message;
  error_code code = error_code::none;
};

template <class T = float>
refusal refusal_of(const std::string& text, const io::scene_limits& limits = {}) {
  try {
    (void)io::parse_scene<T>(text, "limits.json", limits);
  } catch (const io::scene_error& e) {
    CHECK(e.file() == "limits.json");
    return {true, e.path(), e.what(), e.code()};
  }
  return {};
}

/// `count` copies of `item`, comma-separated.
std::string repeated(const std::string& item, std::size_t count) {
  std::string out;
  out.reserve(count * (item.size() + 1));
  for (std::size_t i = 0; i < count; ++i) out += (i ? "," : "") + item;
  return out;
}

/// A convex hull of `points` points (a tetrahedron's corners, then copies of its first).
std::string hull(std::size_t points) {
  // Appended piece by piece: g++ 12 at -O3 took "," + a temporary for an
  // overlapping copy (-Wrestrict, a false positive).
  std::string out = R"({"type": "convex_hull", "vertices": [[0,0,0],[1,0,0],[0,1,0],[0,0,1])";
  if (points > 4) out += ',', out += repeated("[0,0,0]", points - 4);
  return out + "]}";
}

/// A triangle mesh of `vertices` vertices (one triangle, then unused points) and `triangles` triangles.
std::string mesh(std::size_t vertices, std::size_t triangles = 1) {
  std::string out = R"({"type": "triangle_mesh", "vertices": [[0,0,0],[1,0,0],[0,1,0])";
  if (vertices > 3) out += ',', out += repeated("[0,0,0]", vertices - 3);
  return out + R"(], "triangles": [)" + repeated("[0,1,2]", triangles) + "]}";
}

/// A compound of `children` balls.
std::string balls_compound(std::size_t children) {
  const std::string ball_child = R"({"shape": {"type": "sphere", "radius": 0.1}})";
  return R"({"type": "compound", "children": [)" + repeated(ball_child, children) + "]}";
}

const std::string head = R"({"impulse_scene": 1, )";
const std::string ball = R"({"shape": {"type": "sphere", "radius": 0.1}})";

}  // namespace

TEST_CASE("a document past scene_limits::bytes is refused by its size, before it is parsed") {
  // 64 MiB and a byte of an unfinished document: a parse would call it "not
  // JSON"; the size alone refuses it, so nothing was parsed.
  const std::size_t size = io::scene_limits{}.bytes + 1;
  std::string text = head + R"("description": ")";
  text.resize(size, 'x');
  const refusal r = refusal_of(text);
  CHECK(r.refused);
  CHECK(r.path == "");
  CHECK(r.code == error_code::capacity_exceeded);
  CHECK(r.message.find("limits.json: (document): 67108865 bytes, more than the 67108864") == 0);
}

TEST_CASE("a file past scene_limits::bytes is refused by its size before it is read, and one at the limit loads") {
  const std::string text = head + R"("description": "padding"})";
  const std::filesystem::path file = std::filesystem::temp_directory_path() / "impulse_scene_limits_bytes.json";
  {
    std::ofstream out(file, std::ios::binary);
    out << text;
  }
  io::scene_limits limits;
  limits.bytes = text.size();
  CHECK_NOTHROW((void)io::read_scene<float>(file.string(), limits));
  limits.bytes = text.size() - 1;
  try {
    (void)io::read_scene<float>(file.string(), limits);
    FAIL("a file one byte past the limit was read");
  } catch (const io::scene_error& e) {
    CHECK(e.path() == "");
    CHECK(e.code() == error_code::capacity_exceeded);
    CHECK(std::string(e.what()).find(std::to_string(text.size()) + " bytes, more than the") != std::string::npos);
  }
  std::filesystem::remove(file);
}

TEST_CASE("particle capacities are summed over all systems and the system that crosses the limit is named") {
  // The 323 KB file that asked for 10.7 GB in miniature: systems of the
  // largest capacity one after the other. The second is refused.
  const std::string big = R"({"capacity": 16777216})";
  const refusal many = refusal_of(head + R"("particles": [)" + repeated(big, 1000) + "]}");
  CHECK(many.refused);
  CHECK(many.path == "/particles/1/capacity");
  CHECK(many.code == error_code::capacity_exceeded);
  CHECK(many.message.find("more than 16777216 particles (scene_limits::particles)") != std::string::npos);

  // Exactly the limit, split over two systems, loads.
  const refusal halves = refusal_of(head + R"("particles": [{"capacity": 8388608}, {"capacity": 8388608}]})");
  CHECK_MESSAGE(!halves.refused, halves.message);
  CHECK(refusal_of(head + R"("particles": [{"capacity": 8388608}, {"capacity": 8388609}]})").path ==
        "/particles/1/capacity");
}

TEST_CASE("particle capacities are checked for all systems before any system's particles are read") {
  // System 0 nearly fills its capacity by repeats (16.7 million particles,
  // over 500 MB of scene) and then gives a bad mass. Were the capacities summed system by system,
  // the first error would be that mass, after making the particles; summed
  // first, the error is system 1's capacity and no particle was made.
  const std::string fill = R"({"position": [0, 0, 0], "repeat": {"count": 100000, "step": {"position": [0.001, 0, 0]}}})";
  const std::string first = R"({"capacity": 16777216, "particles": [)" + repeated(fill, 167) +
                            R"(, {"position": [0, 0, 0], "mass": -1}]})";
  const refusal r = refusal_of(head + R"("particles": [)" + first + R"(, {"capacity": 1}]})");
  CHECK(r.path == "/particles/1/capacity");
  CHECK(r.code == error_code::capacity_exceeded);
}

TEST_CASE("each limit holds over the whole document and can be lowered: at it a scene loads, past it the crossing value is named") {
  using limit = std::size_t io::scene_limits::*;
  const struct {
    const char* name;
    limit member;
    std::size_t value;
    std::string at_limit, past_limit, path;
  } cases[] = {
      {"bodies", &io::scene_limits::bodies, 5,
       head + R"("bodies": [)" + ball + R"(, {"shape": {"type": "sphere", "radius": 0.1}, "repeat": {"count": [2, 2, 1], "spacing": [1, 1, 1]}}]})",
       head + R"("bodies": [)" + ball + "," + ball + R"(, {"shape": {"type": "sphere", "radius": 0.1}, "repeat": {"count": [2, 2, 1], "spacing": [1, 1, 1]}}]})",
       "/bodies/2"},
      {"joints", &io::scene_limits::joints, 2,
       head + R"("bodies": [{"name": "a", "shape": {"type": "sphere", "radius": 0.1}, "repeat": {"count": 4, "step": {"position": [1, 0, 0]}}}],
                 "joints": [{"type": "ball", "a": "a[0]", "b": "a[1]", "anchor": [0, 0, 0], "repeat": {"count": 2}}]})",
       head + R"("bodies": [{"name": "a", "shape": {"type": "sphere", "radius": 0.1}, "repeat": {"count": 4, "step": {"position": [1, 0, 0]}}}],
                 "joints": [{"type": "ball", "a": "a[0]", "b": "a[1]", "anchor": [0, 0, 0]},
                            {"type": "ball", "a": "a[1]", "b": "a[2]", "anchor": [0, 0, 0], "repeat": {"count": 2}}]})",
       "/joints/1"},
      {"particles", &io::scene_limits::particles, 10,
       head + R"("particles": [{"capacity": 4}, {"capacity": 6}]})",
       head + R"("particles": [{"capacity": 4}, {"capacity": 7}]})", "/particles/1/capacity"},
      {"hull_points", &io::scene_limits::hull_points, 6,
       head + R"("shapes": {"a": )" + hull(6) + "}}",
       head + R"("shapes": {"a": )" + hull(7) + "}}", "/shapes/a/vertices"},
      {"vertices", &io::scene_limits::vertices, 11,
       head + R"("shapes": {"a": )" + hull(4) + R"(, "b": )" + mesh(3) + R"(, "c": )" + hull(4) + "}}",
       head + R"("shapes": {"a": )" + hull(4) + R"(, "b": )" + mesh(4) + R"(, "c": )" + hull(4) + "}}",
       "/shapes/c/vertices"},
      {"triangles", &io::scene_limits::triangles, 5,
       head + R"("shapes": {"a": )" + mesh(3, 2) + R"(, "b": )" + mesh(3, 3) + "}}",
       head + R"("shapes": {"a": )" + mesh(3, 2) + R"(, "b": )" + mesh(3, 4) + "}}", "/shapes/b/triangles"},
      {"compound_children", &io::scene_limits::compound_children, 5,
       head + R"("shapes": {"a": )" + balls_compound(2) + R"(, "b": )" + balls_compound(3) + "}}",
       head + R"("shapes": {"a": )" + balls_compound(2) + R"(, "b": )" + balls_compound(4) + "}}",
       "/shapes/b/children"},
      // 7 values: the document, 1, the settings, the gravity and its 3
      // numbers. With a duration as well, gravity's last number is the 8th.
      {"json_values", &io::scene_limits::json_values, 7, head + R"("settings": {"gravity": [0, -9.81, 0]}})",
       head + R"("duration": 1, "settings": {"gravity": [0, -9.81, 0]}})", "/settings/gravity/2"},
  };
  for (const auto& c : cases) {
    CAPTURE(c.name);
    io::scene_limits limits;
    limits.*c.member = c.value;
    const refusal at = refusal_of(c.at_limit, limits);
    CHECK_MESSAGE(!at.refused, at.message);
    const refusal past = refusal_of(c.past_limit, limits);
    CHECK(past.refused);
    CHECK(past.path == c.path);
    CHECK(past.code == error_code::capacity_exceeded);
    CHECK_MESSAGE(past.message.find(std::string("(scene_limits::") + c.name + ")") != std::string::npos, past.message);
    const refusal defaults = refusal_of(c.past_limit);
    CHECK_MESSAGE(!defaults.refused, defaults.message);
  }

  // The ball is 4 levels down (document, bodies, body, shape); a rotation's
  // axis is 5.
  io::scene_limits shallow;
  shallow.depth = 4;
  const refusal ball_at_limit = refusal_of(head + R"("bodies": [{"shape": {"type": "sphere", "radius": 1}}]})", shallow);
  CHECK_MESSAGE(!ball_at_limit.refused, ball_at_limit.message);
  const refusal deep = refusal_of(
      head + R"("bodies": [{"rotation": {"axis": [0, 1, 0], "degrees": 5}, "shape": {"type": "sphere", "radius": 1}}]})",
      shallow);
  CHECK(deep.path == "/bodies/0/rotation/axis");
  CHECK(deep.code == error_code::capacity_exceeded);
  CHECK(deep.message.find("nested deeper than 4 levels (scene_limits::depth)") != std::string::npos);
}

TEST_CASE("a compound past the default compound_children is refused before its children are built") {
  // One child more than scene_limits::compound_children and compound::max_children (both 2^16).
  const std::size_t most = io::scene_limits{}.compound_children;
  REQUIRE(most == compound<float>::max_children);
  const std::string one_more = head + R"("bodies": [{"shape": )" + balls_compound(most + 1) + "}]}";
  const refusal past = refusal_of(one_more);
  CHECK(past.path == "/bodies/0/shape/children");
  CHECK(past.code == error_code::capacity_exceeded);
  CHECK_MESSAGE(past.message.find("(scene_limits::compound_children)") != std::string::npos, past.message);
  CHECK(!refusal_of(head + R"("bodies": [{"shape": )" + balls_compound(most) + "}]}").refused);
  // With the limit raised, one compound still takes no more than max_children:
  // the builder's refusal names the child past it.
  io::scene_limits raised;
  raised.compound_children = 2 * most;
  const refusal builder = refusal_of(one_more, raised);
  CHECK(builder.path == "/bodies/0/shape/children/" + std::to_string(most));
  CHECK_MESSAGE(builder.message.find("max_children") != std::string::npos, builder.message);
}

TEST_CASE("a hull named by a compound's children counts its vertices again for each child that copies it") {
  // The hull's 4 points, then 4 vertices for each of the 3 children that name it: 16.
  const std::string copies = R"({"type": "compound", "children": [{"shape": "h"}, {"shape": "h"}, {"shape": "h"}]})";
  const std::string text = head + R"("shapes": {"h": )" + hull(4) + R"(, "c": )" + copies + "}}";
  io::scene_limits limits;
  limits.vertices = 16;
  const refusal at = refusal_of(text, limits);
  CHECK_MESSAGE(!at.refused, at.message);
  limits.vertices = 15;
  const refusal past = refusal_of(text, limits);
  CHECK(past.path == "/shapes/c/children/2/shape");
  CHECK(past.code == error_code::capacity_exceeded);
  CHECK_MESSAGE(past.message.find("(scene_limits::vertices)") != std::string::npos, past.message);
}

TEST_CASE("a key given twice in one object is refused naming its path") {
  const struct {
    std::string text, path;
  } cases[] = {
      {R"({"impulse_scene": 1, "impulse_scene": 1})", "/impulse_scene"},
      {head + R"("bodies": [{"shape": {"type": "sphere", "radius": 1, "radius": 2}}]})", "/bodies/0/shape/radius"},
      {head + R"("bodies": [)" + ball + R"(, {"name": "a", "name": "b", "shape": {"type": "sphere", "radius": 1}}]})",
       "/bodies/1/name"},
      // RFC 6901 escapes '/' in a key as "~1".
      {head + R"("shapes": {"a/b": {"type": "sphere", "radius": 1}, "a/b": {"type": "sphere", "radius": 2}}})",
       "/shapes/a~1b"},
  };
  for (const auto& c : cases) {
    CAPTURE(c.text);
    const refusal r = refusal_of(c.text);
    CHECK(r.refused);
    CHECK(r.path == c.path);
    CHECK(r.message.find("is given twice in this object") != std::string::npos);
  }
  // The same key in two different objects is fine.
  CHECK(!refusal_of(head + R"("bodies": [)" + ball + "," + ball + "]}").refused);
}

TEST_CASE("a particle mass too small to invert and an emitter rate past max_rate are refused where the file gives them") {
  // 1e-45 is a denormal float, whose inverse overflows: add_particles would
  // have stored an infinite inverse mass, and drag made the particle NaN.
  const struct {
    std::string text, path, message;
  } cases[] = {
      {head + R"("particles": [{"capacity": 2, "particles": [{"position": [0, 0, 0], "mass": 1e-45}]}]})",
       "/particles/0/particles/0/mass", "expected a mass of at least 1.1754943508222875e-38"},
      {head + R"("particles": [{"capacity": 2, "emitters": [{"mass": 1e-45}]}]})", "/particles/0/emitters/0/mass",
       "expected a mass of at least"},
      {head + R"("particles": [{"capacity": 2, "emitters": [{"rate": 1e30}]}]})", "/particles/0/emitters/0/rate",
       "expected a number in [0, 1000000000], got 1e+30"},
  };
  for (const auto& c : cases) {
    CAPTURE(c.text);
    const refusal r = refusal_of(c.text);
    CHECK(r.path == c.path);
    CHECK_MESSAGE(r.message.find(c.message) != std::string::npos, r.message);
  }
  // 1e-45 is a normal double: a double scene takes it, and its system steps to finite values.
  const io::scene<double> scene = io::parse_scene<double>(
      head + R"("particles": [{"capacity": 2, "forces": {"drag": {}}, "particles": [{"position": [0, 1, 0], "velocity": [0, 0, 0], "mass": 1e-45}]}]})");
  struct config : default_config {
    using scalar = double;
  };
  auto system = io::make_particles<particle_system<config, particles::drag>>(scene.particle_systems[0]);
  system.step(1e-3);
  CHECK(std::isfinite(system.position(0).y));
  CHECK(std::isfinite(system.inverse_masses()[0]));
}

TEST_CASE("a whole number written as a float at or past 2^63 is refused, not converted to int64") {
  // double(INT64_MAX) rounds up to 2^63, which int64_t cannot hold.
  const std::string file = "numbers.json";
  const io::detail::json_reader<double> reader(file);
  const auto integer = [&](double x) {
    const io::detail::json value = x;
    return reader.integer({value, "/n", &file}, 0, std::numeric_limits<std::int64_t>::max());
  };
  constexpr std::int64_t two_to_62 = std::int64_t(1) << 62;
  CHECK(integer(4611686018427387904.0) == two_to_62);
  CHECK_THROWS_AS((void)integer(9223372036854775808.0), io::scene_error);
  CHECK_THROWS_AS((void)integer(1e300), io::scene_error);
}
