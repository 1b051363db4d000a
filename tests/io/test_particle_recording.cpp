// Particle recordings (io/particle_recording.hpp): a run read back is the
// run, frame by frame and bit for bit; the file's size is its documented
// layout; colors follow age and speed along their ramps; a file cut short
// or of another kind is refused.
#include <doctest/doctest.h>

#include <cstdint>
#include <vector>

#include "impulse/io/particle_recording.hpp"
#include "impulse/particles.hpp"

namespace io_particle_recording_tests {

using namespace impulse;
using namespace impulse::particles;

TEST_CASE("a particle run read back from its recording is the run frame by frame") {
  particle_system<default_config, gravity> fountain(500);
  fountain.add_emitter({.position = {0, 0, 0}, .velocity = {0, 5, 0}, .velocity_spread = {1, 1, 1}, .rate = 600,
                        .lifetime = 0.5f, .lifetime_spread = 0.1f});
  io::particle_recorder recording;
  std::vector<std::vector<vec3<float>>> seen;
  std::size_t particle_frames = 0;
  for (int i = 0; i < 60; ++i) {
    fountain.step(1.0f / 60);
    recording.record(fountain);
    seen.emplace_back();
    for (std::size_t k = 0; k < fountain.size(); ++k) seen.back().push_back(fountain.positions()[k]);
    particle_frames += fountain.size();
  }
  const std::vector<std::uint8_t> file = recording.ipr();
  CHECK(file.size() == 48 + 60 * 8 + 12 * particle_frames);  // the layout, no colors

  const auto back = io::read_particle_recording(file);
  REQUIRE(back);
  CHECK(!back->colored);
  CHECK(back->interval == doctest::Approx(1.0f / 60));
  REQUIRE(back->frames.size() == 60);
  CHECK(seen[59].size() > 200);  // about rate × lifetime alive: births and deaths are in the run
  for (std::size_t f = 0; f < 60; ++f) {
    REQUIRE(back->frames[f].positions.size() == seen[f].size());
    CHECK(back->frames[f].time == doctest::Approx(float(f + 1) / 60));
    for (std::size_t k = 0; k < seen[f].size(); ++k) {
      const vec3<float>& p = back->frames[f].positions[k];
      CHECK(p == seen[f][k]);
      CHECK((p.x >= back->lower.x && p.y >= back->lower.y && p.z >= back->lower.z));
      CHECK((p.x <= back->upper.x && p.y <= back->upper.y && p.z <= back->upper.z));
    }
  }
  // Cut short anywhere, or not a recording, it is refused.
  for (const std::size_t cut : {std::size_t(10), std::size_t(47), std::size_t(60), file.size() - 1})
    CHECK(!io::read_particle_recording(std::vector<std::uint8_t>(file.begin(), file.begin() + std::ptrdiff_t(cut))));
  std::vector<std::uint8_t> other = file;
  other[0] = 'X';
  CHECK(!io::read_particle_recording(other));
}

TEST_CASE("particle colors follow age over lifetime and speed along their ramps") {
  particle_system<default_config, drag> still(8, drag<float>{.coefficient = 0});
  still.add({0, 0, 0}, {0, 0, 0}, 1, 2);     // at rest, lives 2 s
  still.add({1, 0, 0}, {10, 0, 0}, 1, 2);    // at full speed
  still.add({2, 0, 0}, {5, 0, 0}, 1, 1000);  // half speed, long-lived
  still.step(1);                             // ages 1 s: half of 2 s

  io::particle_recorder by_age(io::color_by::age), by_speed(io::color_by::speed, 10);
  by_age.record(still);
  by_speed.record(still);
  const auto age = io::read_particle_recording(by_age.ipr());
  const auto speed = io::read_particle_recording(by_speed.ipr());
  REQUIRE(age);
  REQUIRE(speed);
  CHECK(age->colored);
  CHECK(by_age.ipr().size() == 48 + 8 + 3 * 12 + 12);  // 9 color bytes padded to 12
  const auto& a = age->frames[0].colors;
  CHECK(a[0] == io::ramp(io::color_by::age, 0.5));
  CHECK(a[2] == io::ramp(io::color_by::age, 0.001));
  const auto& s = speed->frames[0].colors;
  CHECK(s[0] == io::ramp(io::color_by::speed, 0));
  CHECK(s[1] == io::ramp(io::color_by::speed, 1));
  CHECK(s[2] == io::ramp(io::color_by::speed, 0.5));
  // The ramps' ends: white-hot to dark red by age, blue to red by speed.
  CHECK(io::ramp(io::color_by::age, 0) == std::array<std::uint8_t, 3>{255, 250, 220});
  CHECK(io::ramp(io::color_by::age, 2) == std::array<std::uint8_t, 3>{90, 20, 10});
  CHECK(io::ramp(io::color_by::speed, 0)[2] > 200);
  CHECK(io::ramp(io::color_by::speed, 1)[0] > 200);
}

}  // namespace io_particle_recording_tests
