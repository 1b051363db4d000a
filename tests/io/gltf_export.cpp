// The glTF recording (io/gltf.hpp) read back with nlohmann::json (Debian's
// nlohmann-json3-dev): the GLB container, every accessor inside its view
// and every view inside the buffer, the meshes shared where shapes are the
// same, a compound's one mesh spanning its children, and the animation's
// last frame where the world left each body.
// Its own executable, built when nlohmann-json is installed: the library
// never needs it.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <nlohmann/json.hpp>
#include <vector>

#include "../world/scenes.hpp"
#include "impulse/io/gltf.hpp"
#include "impulse/world.hpp"

using namespace impulse;
using json = nlohmann::json;

namespace {

// The shared test world (tests/world/scenes.hpp), compiled once.
using awake = impulse::test::awake_config;

std::uint32_t word(const std::vector<std::uint8_t>& bytes, std::size_t at) {
  std::uint32_t v = 0;
  std::memcpy(&v, bytes.data() + at, 4);
  return v;
}

struct glb_file {
  json document;
  std::vector<std::uint8_t> bin;

  explicit glb_file(const std::vector<std::uint8_t>& bytes) {
    REQUIRE(bytes.size() >= 20);
    CHECK(word(bytes, 0) == 0x46546C67u);  // "glTF"
    CHECK(word(bytes, 4) == 2);
    CHECK(word(bytes, 8) == bytes.size());
    const std::uint32_t json_length = word(bytes, 12);
    CHECK(json_length % 4 == 0);
    CHECK(word(bytes, 16) == 0x4E4F534Au);  // "JSON"
    document = json::parse(bytes.begin() + 20, bytes.begin() + 20 + json_length);
    const std::size_t bin_at = 20 + json_length;
    if (bytes.size() == bin_at) return;  // no binary chunk
    REQUIRE(bytes.size() >= bin_at + 8);
    const std::uint32_t bin_length = word(bytes, bin_at);
    CHECK(bin_length % 4 == 0);
    CHECK(word(bytes, bin_at + 4) == 0x004E4942u);  // "BIN"
    REQUIRE(bytes.size() == bin_at + 8 + bin_length);
    bin.assign(bytes.begin() + std::ptrdiff_t(bin_at + 8), bytes.end());
  }

  /// Accessor a's floats (every component, in order).
  std::vector<float> floats(int a) const {
    const json& accessor = document["accessors"][std::size_t(a)];
    const json& view = document["bufferViews"][accessor["bufferView"].get<std::size_t>()];
    const std::size_t width = accessor["type"] == "SCALAR" ? 1 : accessor["type"] == "VEC3" ? 3 : 4;
    std::vector<float> out(accessor["count"].get<std::size_t>() * width);
    std::memcpy(out.data(), bin.data() + view["byteOffset"].get<std::size_t>(), out.size() * 4);
    return out;
  }
};

}  // namespace

TEST_CASE("a recorded run is a valid GLB whose animation ends where the world left each body") {
  world_settings<float> settings;
  world<awake> w(settings);
  body_def<float> ground;
  ground.type = body_type::static_body;
  ground.pose.position = {0, -0.5f, 0};
  w.create_body(ground, box<float>::make({10, 0.5f, 10}));
  std::vector<body_id> moving;
  body_def<float> d;
  d.pose.position = {0, 1, 0};
  moving.push_back(w.create_body(d, sphere<float>::make(0.5f)));
  for (const float x : {2.0f, 4.0f}) {  // two boxes of one size: one mesh
    d.pose.position = {x, 1, 0};
    moving.push_back(w.create_body(d, box<float>::make({0.5f, 0.5f, 0.5f})));
  }
  d.pose.position = {-2, 1, 0};
  d.pose.rotation = quat<float>::from_axis_angle({0, 0, 1}, 0.5f);
  moving.push_back(w.create_body(d, capsule<float>::make(0.25f, 0.5f)));
  body_def<float> lift;
  lift.type = body_type::kinematic;
  lift.pose.position = {-4, 0.5f, 0};
  lift.angular_velocity = {0, 1, 0};
  moving.push_back(w.create_body(lift, box<float>::make({0.5f, 0.1f, 0.5f})));

  io::gltf_recorder recording(w);
  for (int i = 0; i < 60; ++i) {
    w.step(1.0f / 60);
    recording.record(w);
  }
  CHECK(recording.frame_count() == 61);
  CHECK(recording.mesh_count() == 5);  // ground, ball, box (twice), capsule, kinematic box

  const glb_file file(recording.glb());
  const json& doc = file.document;
  CHECK(doc["asset"]["version"] == "2.0");
  CHECK(doc["buffers"][0]["byteLength"] == file.bin.size());
  for (const json& view : doc["bufferViews"])
    CHECK(view["byteOffset"].get<std::size_t>() + view["byteLength"].get<std::size_t>() <= file.bin.size());
  for (const json& accessor : doc["accessors"]) {
    const json& view = doc["bufferViews"][accessor["bufferView"].get<std::size_t>()];
    const std::size_t width = accessor["type"] == "SCALAR" ? 1 : accessor["type"] == "VEC3" ? 3 : 4;
    CHECK(accessor["count"].get<std::size_t>() * width * 4 <= view["byteLength"].get<std::size_t>());
  }
  REQUIRE(doc["nodes"].size() == 6);
  REQUIRE(doc["meshes"].size() == 5);
  CHECK(doc["nodes"][2]["mesh"] == doc["nodes"][3]["mesh"]);
  // The ball's positions are bounded by its radius.
  const json& ball_primitive = doc["meshes"][doc["nodes"][1]["mesh"].get<std::size_t>()]["primitives"][0];
  const json& ball_positions = doc["accessors"][ball_primitive["attributes"]["POSITION"].get<std::size_t>()];
  for (int c = 0; c < 3; ++c) {
    CHECK(ball_positions["max"][std::size_t(c)].get<float>() == doctest::Approx(0.5f).epsilon(1e-5));
    CHECK(ball_positions["min"][std::size_t(c)].get<float>() == doctest::Approx(-0.5f).epsilon(1e-5));
  }

  // Two channels (translation, rotation) for each moving body, none for
  // the ground; each sampler runs over the 61 frames, 0 to 1 s.
  const json& animation = doc["animations"][0];
  REQUIRE(animation["channels"].size() == 2 * moving.size());
  for (const json& channel : animation["channels"]) {
    const json& sampler = animation["samplers"][channel["sampler"].get<std::size_t>()];
    const std::vector<float> times = file.floats(sampler["input"].get<int>());
    REQUIRE(times.size() == 61);
    CHECK(times.front() == 0.0f);
    CHECK(times.back() == doctest::Approx(1.0f));
    const std::vector<float> values = file.floats(sampler["output"].get<int>());
    const std::size_t node = channel["target"]["node"].get<std::size_t>();
    CHECK(node >= 1);
    const transform<float> pose = w.shape_pose(moving[node - 1]);
    if (channel["target"]["path"] == "translation") {
      REQUIRE(values.size() == 61 * 3);
      for (int c = 0; c < 3; ++c) CHECK(values[60 * 3 + std::size_t(c)] == pose.position[c]);
    } else {
      REQUIRE(values.size() == 61 * 4);
      // The same rotation, either sign.
      const quat<float> q{values[60 * 4], values[60 * 4 + 1], values[60 * 4 + 2], values[60 * 4 + 3]};
      CHECK(std::abs(dot(q, pose.rotation)) == doctest::Approx(1.0f).epsilon(1e-6));
      // Consecutive frames on one side of the quaternion sphere.
      for (std::size_t f = 1; f < 61; ++f) {
        float agree = 0;
        for (std::size_t c = 0; c < 4; ++c) agree += values[4 * f + c] * values[4 * (f - 1) + c];
        CHECK(agree > 0);
      }
    }
  }
  // The ball fell and came to rest on the ground.
  CHECK(w.body(moving[0]).position.y == doctest::Approx(0.5f).epsilon(0.01));

  const char* path = "gltf_export_test.glb";
  REQUIRE(recording.save(path));
  std::FILE* f = std::fopen(path, "rb");
  REQUIRE(f != nullptr);
  std::fseek(f, 0, SEEK_END);
  CHECK(std::size_t(std::ftell(f)) == recording.glb().size());
  std::fclose(f);
  std::remove(path);
}

TEST_CASE("a compound body records as one mesh of its children placed in its frame") {
  // Two boxes side by side and a ball on top: the node's mesh holds the
  // three children's vertices, and its positions span the compound's box.
  compound<float>::builder b;
  b.add(box<float>::make({0.5f, 0.25f, 0.25f}), {{-0.5f, 0, 0}, quat<float>::identity()});
  b.add(box<float>::make({0.5f, 0.25f, 0.25f}), {{0.5f, 0, 0}, quat<float>::identity()});
  b.add(sphere<float>::make(0.25f), {{0, 0.5f, 0}, quat<float>::identity()});
  const compound<float> shape = b.build();
  world<awake> w;
  body_def<float> d;
  d.pose.position = {0, 2, 0};
  w.create_body(d, shape);
  io::gltf_recorder recording(w);
  w.step(1.0f / 60);
  recording.record(w);
  CHECK(recording.mesh_count() == 1);
  const glb_file file(recording.glb());
  const json& primitive = file.document["meshes"][0]["primitives"][0];
  const json& positions = file.document["accessors"][primitive["attributes"]["POSITION"].get<std::size_t>()];
  CHECK(positions["count"] == io::mesh_of(shape).positions.size());
  const aabb<float> bounds = shape.local_aabb();
  for (int c = 0; c < 3; ++c) {
    CHECK(positions["min"][std::size_t(c)].get<float>() == doctest::Approx(bounds.lower[c]).epsilon(1e-5));
    CHECK(positions["max"][std::size_t(c)].get<float>() == doctest::Approx(bounds.upper[c]).epsilon(1e-5));
  }
}

TEST_CASE("an empty world records as a valid GLB with no nodes and no buffer") {
  // glTF's arrays may not be empty, and a buffer may not be 0 bytes long.
  world<awake> w;
  io::gltf_recorder recording(w);
  w.step(1.0f / 60);
  recording.record(w);
  const std::vector<std::uint8_t> bytes = recording.glb();
  const glb_file file(bytes);
  CHECK(file.bin.empty());
  CHECK(file.document["scenes"][0].is_object());
  CHECK_FALSE(file.document["scenes"][0].contains("nodes"));
  for (const char* key : {"nodes", "meshes", "accessors", "bufferViews", "buffers", "animations"})
    CHECK_FALSE(file.document.contains(key));
}

TEST_CASE("a recording with contacts carries each frame's contact points where the bodies touch") {
  // A box of half-height 0.5 dropped onto the ground (top at y = 0): once it
  // rests, each frame holds its four corner contacts, all at y = 0 (midway
  // between the surfaces, within the speculative margin).
  world<awake> w;
  body_def<float> ground;
  ground.type = body_type::static_body;
  ground.pose.position = {0, -0.5f, 0};
  w.create_body(ground, box<float>::make({10, 0.5f, 10}));
  body_def<float> d;
  d.pose.position = {0, 0.6f, 0};
  w.create_body(d, box<float>::make({0.5f, 0.5f, 0.5f}));
  io::gltf_recorder recording(w, {.contacts = true});
  for (int i = 0; i < 60; ++i) {
    w.step(1.0f / 60);
    recording.record(w);
  }
  CHECK(recording.contact_point_count() > 0);
  const glb_file file(recording.glb());
  const json& contacts = file.document["extras"]["impulse"]["contacts"];
  const std::vector<float> points = file.floats(contacts["points"].get<int>());
  const json& offsets_accessor = file.document["accessors"][contacts["offsets"].get<std::size_t>()];
  CHECK(offsets_accessor["componentType"] == 5125);
  REQUIRE(offsets_accessor["count"] == 62);  // frames + 1
  std::vector<std::uint32_t> offsets(62);
  const json& view = file.document["bufferViews"][offsets_accessor["bufferView"].get<std::size_t>()];
  std::memcpy(offsets.data(), file.bin.data() + view["byteOffset"].get<std::size_t>(), 62 * 4);
  CHECK(offsets.front() == 0);
  CHECK(offsets.back() * 3 == points.size());
  for (std::size_t f = 1; f < offsets.size(); ++f) CHECK(offsets[f] >= offsets[f - 1]);
  CHECK(offsets[61] - offsets[60] == 4);  // resting on its face: four corners
  for (std::uint32_t p = offsets[60]; p < offsets[61]; ++p) {
    CHECK(std::abs(points[3 * p + 1]) < 0.01f);
    CHECK(std::abs(std::abs(points[3 * p]) - 0.5f) < 0.01f);
    CHECK(std::abs(std::abs(points[3 * p + 2]) - 0.5f) < 0.01f);
  }
  // Without the option there are no extras.
  io::gltf_recorder plain(w);
  plain.record(w);
  CHECK(!glb_file(plain.glb()).document.contains("extras"));
  // A file that cannot be written is reported, not thrown.
  CHECK(!plain.save("/nonexistent-directory/run.glb"));
}
