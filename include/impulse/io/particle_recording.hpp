// impulse/io/particle_recording.hpp — a particle run recorded frame by frame
// in a compact binary format (.ipr), which viewer/ plays:
//
//   impulse::io::particle_recorder recording(impulse::io::color_by::age);
//   for (...) { plume.step(dt); recording.record(plume); }
//   recording.save("out/plume.ipr");
//
// The format, all little-endian (docs/recording.md):
//
//   header, 48 bytes:  "IMPULSEP"; u32 version = 1; u32 flags (bit 0: frames
//                      carry colors); u32 frame count; f32 frame interval, s;
//                      f32 bounds min[3], max[3] over every recorded position
//   each frame:        f32 time, s; u32 count; count × 3 f32 positions;
//                      with colors, count × 3 u8 RGB, then zero bytes to the
//                      next multiple of 4
//
// 12 bytes a particle a frame, 15 with colors: a 2 000-particle plume at
// 30 frames a second for 10 s is 8.9 MB. Positions are the particles' own,
// not resampled: a frame has as many particles as were alive.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "../math/vec3.hpp"

namespace impulse::io {

/// How a recording colors its particles.
enum class color_by : std::uint8_t {
  none,   ///< no colors stored: the viewer draws every particle alike
  age,    ///< age over lifetime: white-hot when born, through orange, to dark red (systems with lifetimes)
  speed,  ///< |v| over the recorder's full_speed: blue when still, through green, to red
};

/// The color ramp of `f` in [0, 1] for `mode` (clamped).
inline std::array<std::uint8_t, 3> ramp(color_by mode, double f) {
  f = std::clamp(std::isfinite(f) ? f : 1.0, 0.0, 1.0);
  const auto mix = [f](const std::array<double, 3>* stops, int n) {
    const double x = f * (n - 1);
    const int i = std::min(n - 2, int(x));
    const double t = x - i;
    std::array<std::uint8_t, 3> c{};
    for (int k = 0; k < 3; ++k) c[std::size_t(k)] = std::uint8_t(std::lround(stops[i][std::size_t(k)] * (1 - t) + stops[i + 1][std::size_t(k)] * t));
    return c;
  };
  static const std::array<double, 3> fire[] = {{255, 250, 220}, {255, 180, 60}, {220, 80, 20}, {90, 20, 10}};
  static const std::array<double, 3> cold_to_hot[] = {{40, 80, 220}, {40, 200, 200}, {120, 220, 60}, {230, 60, 30}};
  return mode == color_by::age ? mix(fire, 4) : mix(cold_to_hot, 4);
}

/// A recording read back (for tests and tools).
struct particle_frames {
  struct frame {
    float time = 0;
    std::vector<vec3<float>> positions;
    std::vector<std::array<std::uint8_t, 3>> colors;  ///< empty without colors
  };
  float interval = 0;
  bool colored = false;
  vec3<float> lower{}, upper{};
  std::vector<frame> frames;
};

class particle_recorder {
 public:
  /// `full_speed` (m/s) is the top of the speed ramp.
  explicit particle_recorder(color_by mode = color_by::none, double full_speed = 10) noexcept
      : mode_(mode), full_speed_(full_speed > 0 ? full_speed : 1) {}

  /// Appends the system's particles now as a frame at its time.
  template <class System>
  void record(const System& system) {
    const auto x = system.positions();
    const auto v = system.velocities();
    const std::size_t n = x.size();
    put(float(system.time()));
    put(std::uint32_t(n));
    for (std::size_t i = 0; i < n; ++i) {
      const vec3<float> p{float(x[i].x), float(x[i].y), float(x[i].z)};
      put(p.x), put(p.y), put(p.z);
      if (!any_) lower_ = upper_ = p, any_ = true;
      lower_ = {std::min(lower_.x, p.x), std::min(lower_.y, p.y), std::min(lower_.z, p.z)};
      upper_ = {std::max(upper_.x, p.x), std::max(upper_.y, p.y), std::max(upper_.z, p.z)};
    }
    if (mode_ != color_by::none) {
      for (std::size_t i = 0; i < n; ++i) {
        double f = 0;
        if (mode_ == color_by::speed) {
          f = double(length(v[i])) / full_speed_;
        } else if constexpr (requires { system.ages(); }) {
          const double life = double(system.lifetimes()[i]);
          f = std::isfinite(life) ? double(system.ages()[i]) / life : 0.0;
        }
        const auto c = ramp(mode_, f);
        bytes_.insert(bytes_.end(), c.begin(), c.end());
      }
      bytes_.resize((bytes_.size() + 3) / 4 * 4, 0);
    }
    if (frames_ == 1) interval_ = float(system.time()) - first_time_;
    if (frames_ == 0) first_time_ = float(system.time());
    ++frames_;
  }

  [[nodiscard]] std::size_t frame_count() const noexcept { return frames_; }

  /// The whole file: header, then the frames.
  [[nodiscard]] std::vector<std::uint8_t> ipr() const {
    std::array<std::uint8_t, 48> header{'I', 'M', 'P', 'U', 'L', 'S', 'E', 'P'};
    std::size_t at = 8;
    const auto put_to = [&header, &at](auto value) {
      std::memcpy(header.data() + at, &value, sizeof value);
      if constexpr (std::endian::native == std::endian::big) std::reverse(header.data() + at, header.data() + at + sizeof value);
      at += sizeof value;
    };
    put_to(std::uint32_t(1));
    put_to(std::uint32_t(mode_ != color_by::none ? 1 : 0));
    put_to(std::uint32_t(frames_));
    put_to(interval_);
    for (const float c : {lower_.x, lower_.y, lower_.z, upper_.x, upper_.y, upper_.z}) put_to(c);
    // Sized once and copied into: GCC 12 at -O3 warns falsely on an insert
    // after the header (-Warray-bounds).
    std::vector<std::uint8_t> out(header.size() + bytes_.size());
    std::memcpy(out.data(), header.data(), header.size());
    if (!bytes_.empty()) std::memcpy(out.data() + header.size(), bytes_.data(), bytes_.size());
    return out;
  }

  /// Writes the file; false if it cannot be written.
  bool save(const std::string& path) const {
    const std::vector<std::uint8_t> bytes = ipr();
    std::FILE* file = std::fopen(path.c_str(), "wb");
    if (!file) return false;
    const bool written = std::fwrite(bytes.data(), 1, bytes.size(), file) == bytes.size();
    return std::fclose(file) == 0 && written;
  }

 private:
  template <class V>
  void put(V value) {
    std::uint8_t b[sizeof value];
    std::memcpy(b, &value, sizeof value);
    if constexpr (std::endian::native == std::endian::big) std::reverse(b, b + sizeof value);
    bytes_.insert(bytes_.end(), b, b + sizeof value);
  }

  color_by mode_;
  double full_speed_;
  std::vector<std::uint8_t> bytes_;  ///< the frames
  std::size_t frames_ = 0;
  float first_time_ = 0, interval_ = 0;
  bool any_ = false;
  vec3<float> lower_{}, upper_{};
};

/// Reads a .ipr file's bytes; nullopt if they are not one (wrong magic or
/// version, or cut short).
[[nodiscard]] inline std::optional<particle_frames> read_particle_recording(const std::vector<std::uint8_t>& bytes) {
  std::size_t at = 0;
  bool ok = true;
  const auto get = [&](auto& value) {
    if (at + sizeof value > bytes.size()) {
      ok = false;
      return;
    }
    std::uint8_t b[sizeof value];
    std::memcpy(b, bytes.data() + at, sizeof value);
    if constexpr (std::endian::native == std::endian::big) std::reverse(b, b + sizeof value);
    std::memcpy(&value, b, sizeof value);
    at += sizeof value;
  };
  if (bytes.size() < 48 || std::memcmp(bytes.data(), "IMPULSEP", 8) != 0) return std::nullopt;
  at = 8;
  std::uint32_t version = 0, flags = 0, count = 0;
  particle_frames r;
  get(version), get(flags), get(count), get(r.interval);
  get(r.lower.x), get(r.lower.y), get(r.lower.z), get(r.upper.x), get(r.upper.y), get(r.upper.z);
  if (version != 1) return std::nullopt;
  r.colored = (flags & 1) != 0;
  for (std::uint32_t f = 0; f < count && ok; ++f) {
    particle_frames::frame frame;
    std::uint32_t n = 0;
    get(frame.time), get(n);
    if (!ok || std::uint64_t(n) * 12 > bytes.size() - at) return std::nullopt;
    frame.positions.resize(n);
    for (vec3<float>& p : frame.positions) get(p.x), get(p.y), get(p.z);
    if (r.colored) {
      if (std::uint64_t(n) * 3 > bytes.size() - at) return std::nullopt;
      frame.colors.resize(n);
      for (auto& c : frame.colors) std::memcpy(c.data(), bytes.data() + at, 3), at += 3;
      at = (at + 3) / 4 * 4;
    }
    r.frames.push_back(std::move(frame));
  }
  if (!ok || at != bytes.size()) return std::nullopt;
  return r;
}

}  // namespace impulse::io
