// Pictures of a world (io/picture.hpp): a ball covers the disc its
// silhouette projects to, a compound draws each child and not the gap
// between them, the nearer body hides the farther, a floor under the
// camera is cut at the near plane, and the PNG holds the picture's
// pixels in a stream any reader can take (checked by reading it back here:
// chunk CRCs, stored deflate blocks, Adler-32).
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>
#include <vector>

#include "impulse/io/picture.hpp"
#include "impulse/world.hpp"

namespace io_picture_tests {

using namespace impulse;

namespace {

bool is_sky(const io::image& picture, int x, int y) { return picture.at(x, y) == io::sky_color(y, picture.height); }

std::size_t covered(const io::image& picture) {
  std::size_t n = 0;
  for (int y = 0; y < picture.height; ++y)
    for (int x = 0; x < picture.width; ++x) n += is_sky(picture, x, y) ? 0 : 1;
  return n;
}

std::uint32_t big_endian(const std::vector<std::uint8_t>& b, std::size_t at) {
  return std::uint32_t(b[at]) << 24 | std::uint32_t(b[at + 1]) << 16 | std::uint32_t(b[at + 2]) << 8 | b[at + 3];
}

}  // namespace

TEST_CASE("a ball's picture covers the disc its silhouette projects to") {
  // A sphere of radius r at distance d subtends asin(r/d): on an image of
  // focal length f pixels it is a disc of radius f·r/sqrt(d² - r²). The
  // drawn ball is the 24-segment polyhedron inside the sphere, 1.1 % smaller
  // in outline at its equator; edge pixels count ±0.5 px along the 300 px rim.
  world<default_config> w;
  w.create_body({.pose = {{0, 0, 0}, quat<float>::identity()}}, sphere<float>::make(1));
  const io::camera<float> eye{.position = {0, 0, 10}, .target = {0, 0, 0}, .vertical_fov_degrees = 45,
                              .width = 400, .height = 400};
  const io::image picture = io::render(w, eye);
  const double f = 200 / std::tan(22.5 * std::numbers::pi / 180);
  const double radius = f * 1 / std::sqrt(100.0 - 1.0);
  const double ratio = double(covered(picture)) / (std::numbers::pi * radius * radius);
  CHECK(ratio > 0.96);
  CHECK(ratio < 1.01);
  CHECK(!is_sky(picture, 200, 200));
  CHECK(is_sky(picture, 200, 200 - int(radius) - 3));
}

TEST_CASE("the nearer of two bodies hides the farther in a rendered picture") {
  world<default_config> w;
  body_def<float> far;
  far.type = body_type::static_body;
  far.pose.position = {0, 0, -5};
  w.create_body(far, box<float>::make({2, 2, 0.1f}));  // grey
  body_def<float> near;
  near.pose.position = {0, 0, 0};
  w.create_body(near, box<float>::make({0.5f, 0.5f, 0.5f}));  // orange
  const io::image picture = io::render(w, io::camera<float>{.position = {0, 0, 10}, .target = {}, .width = 200,
                                                              .height = 200});
  const auto center = picture.at(100, 100);
  CHECK(center[0] > center[2] + 60);  // orange: the near box
  const auto edge = picture.at(100, 100 + 30);  // past the near box, on the far one: grey
  CHECK(std::abs(int(edge[0]) - int(edge[2])) < 20);
  CHECK(!is_sky(picture, 100, 130));
}

TEST_CASE("a compound's picture covers each of its children and not the gap between them") {
  // Two balls of radius 0.5 m, 3 m apart, as one body seen from 10 m: each
  // child's center is drawn, the middle between them is sky.
  compound<float>::builder b;
  b.add(sphere<float>::make(0.5f), {{-1.5f, 0, 0}, quat<float>::identity()});
  b.add(sphere<float>::make(0.5f), {{1.5f, 0, 0}, quat<float>::identity()});
  world<default_config> w;
  w.create_body({.pose = {{0, 0, 0}, quat<float>::identity()}}, b.build());
  const io::camera<float> eye{.position = {0, 0, 10}, .target = {0, 0, 0}, .vertical_fov_degrees = 45,
                              .width = 400, .height = 400};
  const io::image picture = io::render(w, eye);
  // 1.5 m to the side at 10 m is f·0.15 pixels from the middle.
  const int offset = int(std::lround(200 / std::tan(22.5 * std::numbers::pi / 180) * 0.15));
  CHECK(!is_sky(picture, 200 - offset, 200));
  CHECK(!is_sky(picture, 200 + offset, 200));
  CHECK(is_sky(picture, 200, 200));
}

TEST_CASE("a floor that runs under the camera is drawn up to the near plane") {
  world<default_config> w;
  body_def<float> ground;
  ground.type = body_type::static_body;
  w.create_body(ground, plane<float>::make({0, 1, 0}, 0));
  const io::image picture =
      io::render(w, io::camera<float>{.position = {0, 2, 0}, .target = {0, 2, -1}, .width = 160, .height = 90});
  // Looking level, the horizon is the middle row: ground below, sky above,
  // up to the plane's 100 m edge, which stands 1.1° below the horizon.
  for (int x = 0; x < 160; x += 10) {
    CHECK(is_sky(picture, x, 10));
    CHECK(!is_sky(picture, x, 80));
  }
}

TEST_CASE("the PNG of a rendered picture reads back as its pixels") {
  io::image picture;
  picture.width = 200, picture.height = 150;  // 90 150 bytes of rows: two stored blocks
  picture.rgb.resize(200 * 150 * 3);
  for (std::size_t i = 0; i < picture.rgb.size(); ++i) picture.rgb[i] = std::uint8_t(i * 7 + i / 601);
  const std::vector<std::uint8_t> file = io::png(picture);

  const std::uint8_t signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  REQUIRE(file.size() > 8);
  CHECK(std::memcmp(file.data(), signature, 8) == 0);
  CHECK(io::detail::crc32(reinterpret_cast<const std::uint8_t*>("IEND"), 4) == 0xAE426082u);  // every PNG's last CRC
  std::vector<std::uint8_t> idat;
  std::size_t at = 8;
  int chunks = 0;
  while (at + 12 <= file.size()) {
    const std::uint32_t n = big_endian(file, at);
    REQUIRE(at + 12 + n <= file.size());
    const std::string type(file.begin() + std::ptrdiff_t(at + 4), file.begin() + std::ptrdiff_t(at + 8));
    CHECK(io::detail::crc32(file.data() + at + 4, 4 + n) == big_endian(file, at + 8 + n));
    if (type == "IHDR") {
      CHECK(big_endian(file, at + 8) == 200);
      CHECK(big_endian(file, at + 12) == 150);
      CHECK(file[at + 16] == 8);  // bit depth
      CHECK(file[at + 17] == 2);  // RGB
    }
    if (type == "IDAT") idat.insert(idat.end(), file.begin() + std::ptrdiff_t(at + 8), file.begin() + std::ptrdiff_t(at + 8 + n));
    ++chunks;
    at += 12 + n;
  }
  CHECK(chunks == 3);
  CHECK(at == file.size());

  // zlib header, stored blocks (LEN and its complement), Adler-32.
  REQUIRE(idat.size() > 6);
  CHECK((idat[0] * 256 + idat[1]) % 31 == 0);
  std::vector<std::uint8_t> raw;
  std::size_t p = 2;
  bool last = false;
  int blocks = 0;
  while (!last) {
    REQUIRE(p + 5 <= idat.size());
    last = idat[p] & 1;
    CHECK((idat[p] >> 1) == 0);  // BTYPE 00
    const unsigned len = idat[p + 1] | idat[p + 2] << 8, nlen = idat[p + 3] | idat[p + 4] << 8;
    CHECK(len == (~nlen & 0xffffu));
    REQUIRE(p + 5 + len <= idat.size());
    raw.insert(raw.end(), idat.begin() + std::ptrdiff_t(p + 5), idat.begin() + std::ptrdiff_t(p + 5 + len));
    p += 5 + len;
    ++blocks;
  }
  CHECK(blocks == 2);
  REQUIRE(p + 4 == idat.size());
  std::uint32_t a = 1, b = 0;
  for (const std::uint8_t byte : raw) a = (a + byte) % 65521, b = (b + a) % 65521;
  CHECK(((b << 16) | a) == big_endian(idat, p));
  REQUIRE(raw.size() == 150 * (1 + 600));
  for (int y = 0; y < 150; ++y) {
    CHECK(raw[std::size_t(y) * 601] == 0);  // filter: none
    CHECK(std::memcmp(raw.data() + std::size_t(y) * 601 + 1, picture.rgb.data() + std::size_t(y) * 600, 600) == 0);
  }
}

}  // namespace io_picture_tests
