// impulse/io/picture.hpp — a picture of a world, drawn on the CPU with no
// graphics library: every body's shape as triangles (io/shape_mesh.hpp),
// seen through a pinhole camera, hidden surfaces removed by a depth buffer,
// each face shaded by its angle to one light (Lambert), and written as a
// PNG. Enough for an example run headless to leave a picture behind.
//
//   impulse::io::camera<float> eye{.position = {9, 6, 10}, .target = {0, 1, 0}};
//   impulse::io::save_png(impulse::io::render(world, eye), "out/run.png");
//
// The PNG is written with stored (uncompressed) deflate blocks (RFC 1950,
// 1951; PNG specification, 2003): a valid file any reader opens, at the size
// of the raw pixels, with no compression library to depend on.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "../dynamics/fwd.hpp"
#include "../dynamics/rigid_body.hpp"
#include "../math/transform.hpp"
#include "shape_mesh.hpp"

namespace impulse::io {

/// A pinhole camera. Units: m and degrees.
template <class T>
struct camera {
  vec3<T> position{T(10), T(6), T(10)};
  vec3<T> target{};
  vec3<T> up{T(0), T(1), T(0)};
  T vertical_fov_degrees = T(45);
  int width = 960, height = 540;  ///< pixels
  /// Nothing nearer than this is drawn, m (triangles crossing it are cut).
  T near = T(0.05);
};

/// 8-bit RGB pixels, rows from the top.
struct image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  ///< width·height·3 bytes
  [[nodiscard]] std::array<std::uint8_t, 3> at(int x, int y) const {
    const std::size_t i = 3 * (std::size_t(y) * std::size_t(width) + std::size_t(x));
    return {rgb[i], rgb[i + 1], rgb[i + 2]};
  }
};

/// The background at row y of h: a pale sky, lighter towards the horizon.
inline std::array<std::uint8_t, 3> sky_color(int y, int h) {
  const double f = h > 1 ? double(y) / double(h - 1) : 0.0;
  return {std::uint8_t(150 + 80 * f), std::uint8_t(180 + 60 * f), std::uint8_t(225 + 25 * f)};
}

namespace detail {

struct raster {
  int width, height;
  std::vector<float> depth;
  image picture;

  raster(int w, int h) : width(w), height(h), depth(std::size_t(w) * std::size_t(h), INFINITY) {
    picture.width = w;
    picture.height = h;
    picture.rgb.resize(std::size_t(w) * std::size_t(h) * 3);
    for (int y = 0; y < h; ++y) {
      const auto c = sky_color(y, h);
      for (int x = 0; x < w; ++x)
        std::copy(c.begin(), c.end(), picture.rgb.begin() + 3 * (std::ptrdiff_t(y) * w + x));
    }
  }

  /// Fills a triangle given in pixels (x right, y down) with its view depth,
  /// pixel centers in, by edge functions; nearer pixels win.
  void fill(const std::array<std::array<double, 3>, 3>& p, const std::array<std::uint8_t, 3>& color) {
    const double area = (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]);
    if (!(std::abs(area) > 1e-12)) return;
    // The bounds are clamped to the raster while still doubles: a corner cut
    // at the near plane can lie 1e13 pixels off screen (a large box around
    // the camera), and converting that to int is undefined behaviour.
    // (NaN corners give a NaN area, refused above.)
    const auto pixel = [](double v, int last) { return int(std::clamp(v, -1.0, double(last) + 1)); };
    const int x0 = std::max(0, pixel(std::floor(std::min({p[0][0], p[1][0], p[2][0]})), width - 1));
    const int x1 = std::min(width - 1, pixel(std::ceil(std::max({p[0][0], p[1][0], p[2][0]})), width - 1));
    const int y0 = std::max(0, pixel(std::floor(std::min({p[0][1], p[1][1], p[2][1]})), height - 1));
    const int y1 = std::min(height - 1, pixel(std::ceil(std::max({p[0][1], p[1][1], p[2][1]})), height - 1));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const double px = x + 0.5, py = y + 0.5;
        double w[3];
        for (int k = 0; k < 3; ++k) {
          const auto& a = p[(k + 1) % 3];
          const auto& b = p[(k + 2) % 3];
          w[k] = ((b[0] - a[0]) * (py - a[1]) - (px - a[0]) * (b[1] - a[1])) / area;
        }
        if (w[0] < 0 || w[1] < 0 || w[2] < 0) continue;
        // Depth is interpolated as 1/z, which is linear on the screen.
        const double inverse = w[0] / p[0][2] + w[1] / p[1][2] + w[2] / p[2][2];
        const float z = float(1 / inverse);
        float& stored = depth[std::size_t(y) * std::size_t(width) + std::size_t(x)];
        if (!(z < stored)) continue;
        stored = z;
        std::copy(color.begin(), color.end(), picture.rgb.begin() + 3 * (std::ptrdiff_t(y) * width + x));
      }
  }
};

inline void append_u32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int s = 24; s >= 0; s -= 8) out.push_back(std::uint8_t(v >> s));
}

inline std::uint32_t crc32(const std::uint8_t* data, std::size_t n, std::uint32_t crc = 0) {
  static const std::array<std::uint32_t, 256> table = [] {
    std::array<std::uint32_t, 256> t{};
    for (std::uint32_t i = 0; i < 256; ++i) {
      std::uint32_t c = i;
      for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      t[i] = c;
    }
    return t;
  }();
  crc = ~crc;
  for (std::size_t i = 0; i < n; ++i) crc = table[(crc ^ data[i]) & 0xff] ^ (crc >> 8);
  return ~crc;
}

inline void append_chunk(std::vector<std::uint8_t>& out, const char* type, const std::vector<std::uint8_t>& body) {
  append_u32(out, std::uint32_t(body.size()));
  const std::size_t start = out.size();
  out.insert(out.end(), type, type + 4);
  out.insert(out.end(), body.begin(), body.end());
  append_u32(out, crc32(out.data() + start, out.size() - start));
}

}  // namespace detail

/// Draws every body of `w` as `eye` sees it. Static bodies are grey, dynamic
/// ones orange, kinematic ones blue, as in the glTF recording; the light
/// comes from over the camera's left shoulder.
template <class World>
[[nodiscard]] image render(const World& w, const camera<typename World::scalar>& eye) {
  using T = typename World::scalar;
  detail::raster r(std::max(1, eye.width), std::max(1, eye.height));
  // The camera's frame: forward f, right s, up u (a right-handed view).
  const vec3<double> from{double(eye.position.x), double(eye.position.y), double(eye.position.z)};
  const vec3<double> to{double(eye.target.x), double(eye.target.y), double(eye.target.z)};
  const vec3<double> up{double(eye.up.x), double(eye.up.y), double(eye.up.z)};
  const vec3<double> f = normalize(to - from);
  const vec3<double> s = normalize(cross(f, up));
  const vec3<double> u = cross(s, f);
  const double focal = 0.5 * r.height / std::tan(0.5 * double(eye.vertical_fov_degrees) * 3.14159265358979323846 / 180);
  const vec3<double> light = normalize(u * 0.8 + f * -0.5 - s * 0.6);
  const double near = std::max(1e-6, double(eye.near));

  for (const body_id id : w.body_ids()) {
    const shape_mesh mesh = w.visit_shape(id, [](const auto& shape) { return mesh_of(shape); });
    const transform<T> pose = w.shape_pose(id);
    const transform<double> place{{double(pose.position.x), double(pose.position.y), double(pose.position.z)},
                                  {double(pose.rotation.x), double(pose.rotation.y), double(pose.rotation.z),
                                   double(pose.rotation.w)}};
    const body_type kind = w.body(id).type;
    const std::array<double, 3> base = kind == body_type::static_body ? std::array<double, 3>{170, 170, 165}
                                       : kind == body_type::kinematic ? std::array<double, 3>{70, 130, 220}
                                                                      : std::array<double, 3>{235, 130, 40};
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
      std::array<vec3<double>, 3> world_corner, view;  // view: (right, up, depth)
      for (std::size_t k = 0; k < 3; ++k) {
        const vec3<float>& c = mesh.positions[mesh.indices[t + k]];
        world_corner[k] = apply(place, vec3<double>{c.x, c.y, c.z});
        const vec3<double> p = world_corner[k] - from;
        view[k] = {dot(p, s), dot(p, u), dot(p, f)};
      }
      const vec3<double> area = cross(world_corner[1] - world_corner[0], world_corner[2] - world_corner[0]);
      if (!(length_squared(area) > 1e-24)) continue;  // no area: nothing to see (a pole's sliver)
      const vec3<double> normal = area / length(area);
      const double shade = 0.35 + 0.65 * std::abs(dot(normal, light));  // two-sided, as a mesh has no inside
      const std::array<std::uint8_t, 3> color{std::uint8_t(base[0] * shade), std::uint8_t(base[1] * shade),
                                               std::uint8_t(base[2] * shade)};
      // Cut at the near plane (Sutherland–Hodgman against depth = near):
      // a floor that runs under the camera is drawn up to it.
      std::vector<vec3<double>> polygon;
      for (int k = 0; k < 3; ++k) {
        const vec3<double>& a = view[std::size_t(k)];
        const vec3<double>& b = view[std::size_t((k + 1) % 3)];
        if (a.z >= near) polygon.push_back(a);
        if ((a.z >= near) != (b.z >= near)) polygon.push_back(a + (b - a) * ((near - a.z) / (b.z - a.z)));
      }
      const auto screen = [&](const vec3<double>& v) {
        return std::array<double, 3>{0.5 * r.width + focal * v.x / v.z, 0.5 * r.height - focal * v.y / v.z, v.z};
      };
      for (std::size_t k = 1; k + 1 < polygon.size(); ++k)
        r.fill({screen(polygon[0]), screen(polygon[k]), screen(polygon[k + 1])}, color);
    }
  }
  return std::move(r.picture);
}

/// The image as a PNG file's bytes: 8-bit RGB, no interlace, filter 0 on
/// every row, the zlib stream made of stored blocks.
[[nodiscard]] inline std::vector<std::uint8_t> png(const image& picture) {
  std::vector<std::uint8_t> raw;  // each row: filter byte 0, then its pixels
  const std::size_t row = 3 * std::size_t(picture.width);
  raw.reserve((row + 1) * std::size_t(picture.height));
  for (int y = 0; y < picture.height; ++y) {
    raw.push_back(0);
    raw.insert(raw.end(), picture.rgb.begin() + std::ptrdiff_t(row) * y, picture.rgb.begin() + std::ptrdiff_t(row) * (y + 1));
  }
  std::vector<std::uint8_t> z{0x78, 0x01};  // deflate, 32 KiB window, no dictionary
  for (std::size_t at = 0; at < raw.size() || at == 0; at += 65535) {
    const std::size_t n = std::min<std::size_t>(65535, raw.size() - at);
    z.push_back(at + n >= raw.size() ? 1 : 0);  // BFINAL, BTYPE = 00 (stored)
    z.push_back(std::uint8_t(n)), z.push_back(std::uint8_t(n >> 8));
    z.push_back(std::uint8_t(~n)), z.push_back(std::uint8_t(~n >> 8));
    z.insert(z.end(), raw.begin() + std::ptrdiff_t(at), raw.begin() + std::ptrdiff_t(at + n));
    if (raw.empty()) break;
  }
  std::uint32_t a = 1, b = 0;  // Adler-32 of the uncompressed data
  for (const std::uint8_t byte : raw) a = (a + byte) % 65521, b = (b + a) % 65521;
  detail::append_u32(z, (b << 16) | a);

  std::vector<std::uint8_t> out{0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  std::vector<std::uint8_t> header;
  detail::append_u32(header, std::uint32_t(picture.width));
  detail::append_u32(header, std::uint32_t(picture.height));
  header.insert(header.end(), {8, 2, 0, 0, 0});  // 8 bits, RGB, deflate, filter 0, no interlace
  detail::append_chunk(out, "IHDR", header);
  detail::append_chunk(out, "IDAT", z);
  detail::append_chunk(out, "IEND", {});
  return out;
}

/// Writes the image as a PNG; false if the file cannot be written.
inline bool save_png(const image& picture, const std::string& path) {
  const std::vector<std::uint8_t> bytes = png(picture);
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (!file) return false;
  const bool written = std::fwrite(bytes.data(), 1, bytes.size(), file) == bytes.size();
  return std::fclose(file) == 0 && written;
}

}  // namespace impulse::io
