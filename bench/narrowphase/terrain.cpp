// bench/narrowphase terrain: the same terrain as a heightfield and as a
// triangle mesh of the same triangles: bytes each holds, and the time of a
// pair test against it (narrowphase::collide, margin 0.02 m) for a ball, a
// box and a capsule at seeded poses just above and into the ground, and of
// a ray cast down onto it, in the same run.
//
// The terrain: 257 × 257 samples 0.5 m apart (a 128 m square, 131 072
// triangles) of rolling hills, y = 1.5·sin(x/7)·cos(z/9) + 0.3·sin(x)·sin(z).
// Timing: each case runs once per round over its 4 096 poses, the cases
// interleaved, for 7 rounds; ns_per_query is the median over the rounds of
// one pass divided by the number of poses.
//
//   cmake --build build/native --target terrain && build/native/bench/narrowphase/terrain
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "impulse/core/random.hpp"
#include "impulse/narrowphase.hpp"
#include "impulse/shapes.hpp"

using namespace impulse;
using T = float;

namespace {

constexpr std::size_t side = 257;
constexpr T spacing = 0.5f;

T hill(T x, T z) { return T(1.5) * std::sin(x / 7) * std::cos(z / 9) + T(0.3) * std::sin(x) * std::sin(z); }

struct pose_set {
  std::vector<transform<T>> poses;
  std::vector<ray<T>> rays;
};

pose_set make_poses() {
  lcg32 random{2026};
  pose_set s;
  for (int n = 0; n < 4096; ++n) {
    const T x = random.uniform<T>(2, 126), z = random.uniform<T>(2, 126);
    const T y = hill(x, z) + random.uniform<T>(-0.3f, 0.6f);
    const quat<T> q = normalize(quat<T>{random.uniform<T>(-1, 1), random.uniform<T>(-1, 1), random.uniform<T>(-1, 1),
                                        random.uniform<T>(0.1f, 1)});
    s.poses.push_back({{x, y, z}, q});
    s.rays.push_back({{x, 10, z}, {random.uniform<T>(-2, 2), -20, random.uniform<T>(-2, 2)}});
  }
  return s;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main() {
  std::vector<T> heights(side * side);
  for (std::size_t k = 0; k < side; ++k)
    for (std::size_t i = 0; i < side; ++i) heights[k * side + i] = hill(T(i) * spacing, T(k) * spacing);
  const heightfield<T> field = heightfield<T>::make(side, side, spacing, spacing, heights);
  std::vector<vec3<T>> points;
  std::vector<std::uint32_t> indices;
  for (std::size_t k = 0; k < side; ++k)
    for (std::size_t i = 0; i < side; ++i) points.push_back({T(i) * spacing, heights[k * side + i], T(k) * spacing});
  for (std::size_t t = 0; t < field.triangle_count(); ++t) {
    const std::size_t cell = t / 2, i = cell % (side - 1), k = cell / (side - 1);
    const auto at = [&](std::size_t a, std::size_t b) { return std::uint32_t(b * side + a); };
    if (t % 2 == 0) indices.insert(indices.end(), {at(i, k), at(i, k + 1), at(i + 1, k + 1)});
    else indices.insert(indices.end(), {at(i, k), at(i + 1, k + 1), at(i + 1, k)});
  }
  const triangle_mesh<T> mesh = triangle_mesh<T>::make(points, indices);
  const pose_set set = make_poses();
  const transform<T> at = transform<T>::identity();
  const sphere<T> ball = sphere<T>::make(0.4f);
  const box<T> crate = box<T>::make({0.4f, 0.3f, 0.5f});
  const capsule<T> pill = capsule<T>::make(0.25f, 0.5f);

  struct bench_case {
    std::string query, shape;
    std::function<std::size_t()> run;
    std::vector<double> ns;
  };
  std::vector<bench_case> cases;
  std::array<contact_manifold<T>, 4> out;
  const std::span<contact_manifold<T>> span(out.data(), out.size());
  const auto add_collide = [&](const char* name, const auto& probe) {
    cases.push_back({std::string("collide_") + name, "heightfield", [&, probe] {
                       std::size_t n = 0;
                       for (const transform<T>& p : set.poses) n += narrowphase::collide(field, at, probe, p, T(0.02), span);
                       return n;
                     }, {}});
    cases.push_back({std::string("collide_") + name, "triangle_mesh", [&, probe] {
                       std::size_t n = 0;
                       for (const transform<T>& p : set.poses) n += narrowphase::collide(mesh, at, probe, p, T(0.02), span);
                       return n;
                     }, {}});
  };
  add_collide("sphere", ball);
  add_collide("box", crate);
  add_collide("capsule", pill);
  cases.push_back({"ray_cast", "heightfield", [&] {
                     std::size_t n = 0;
                     for (const ray<T>& r : set.rays) n += bool(narrowphase::ray_cast(r, field, at));
                     return n;
                   }, {}});
  cases.push_back({"ray_cast", "triangle_mesh", [&] {
                     std::size_t n = 0;
                     for (const ray<T>& r : set.rays) n += bool(narrowphase::ray_cast(r, mesh, at));
                     return n;
                   }, {}});
  std::vector<std::size_t> results(cases.size());
  for (int round = 0; round < 7; ++round)
    for (std::size_t c = 0; c < cases.size(); ++c) {
      const auto start = std::chrono::steady_clock::now();
      results[c] = cases[c].run();
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      cases[c].ns.push_back(1e9 * s / double(set.poses.size()));
    }
  std::printf("query,shape,ns_per_query,results,bytes,bytes_per_sample\n");
  for (std::size_t c = 0; c < cases.size(); ++c) {
    const std::size_t bytes = cases[c].shape == "heightfield" ? field.memory_bytes() : mesh.memory_bytes();
    std::printf("%s,%s,%.1f,%zu,%zu,%.1f\n", cases[c].query.c_str(), cases[c].shape.c_str(), median(cases[c].ns),
                results[c], bytes, double(bytes) / double(side * side));
  }
}
