// Particles stepped across workers: the same bits as one thread, whatever
// the worker count and however the scheduler cuts and orders the ranges.
// Ageing, death, emission, wind and springs are all in the scenes, since
// each keeps something across batches (dead batches, springs' sums).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "../core/schedulers.hpp"
#include "../error_code_of.hpp"
#include "impulse/thread_pool.hpp"
#include "particle_test.hpp"

namespace particles_threads_tests {

namespace {

using namespace impulse::particles;
using impulse::vec3;
namespace in = impulse::integrators;

using impulse::test::backwards_scheduler;

/// Every position and velocity's bits, in index order.
template <class System>
std::vector<unsigned char> bits(const System& s) {
  using T = typename System::scalar;
  std::vector<unsigned char> out;
  const auto p = s.positions(), v = s.velocities();
  for (std::size_t i = 0; i < s.size(); ++i)
    for (T value : {p.x[i], p.y[i], p.z[i], v.x[i], v.y[i], v.z[i]}) {
      unsigned char b[sizeof(T)];
      std::memcpy(b, &value, sizeof(T));
      out.insert(out.end(), b, b + sizeof(T));
    }
  return out;
}

/// The particles scene with wind, short lives and an emitter that refills
/// what dies: 20 000 particles, 1 250 float batches, 60 steps.
template <class C>
std::vector<unsigned char> snow(const impulse::task_system* tasks) {
  using T = typename C::scalar;
  const std::size_t n = 20000;
  particle_system<C, gravity, drag, point_forces, wind> s{n};
  if (tasks) s.set_task_system(*tasks);
  auto& points = s.template force<point_forces>();
  points.add({0, 5, 0}, 20);
  points.add({5, 3, -4}, -15);
  const T r = T(0.70710678118654752);
  s.add_plane(plane_collider<T>::half_space({0, 1, 0}, 0, T(0.5), T(0.2)));
  s.add_plane(plane_collider<T>::half_space({-r, 0, -r}, 10, T(0.5), T(0.2)));
  impulse::lcg32 random{4242};
  for (std::size_t i = 0; i < n - 500; ++i) {
    const vec3<T> x{random.uniform<T>(-8, 8), random.uniform<T>(T(0.5), 15), random.uniform<T>(-8, 8)};
    const vec3<T> v{random.uniform<T>(-5, 5), random.uniform<T>(-5, 5), random.uniform<T>(-5, 5)};
    s.add(x, v, T(1), random.uniform<T>(T(0.05), T(0.6)));
  }
  emitter<T> source;
  source.position = {0, 12, 0};
  source.half_extents = {8, 0, 8};
  source.rate = 12000;
  source.lifetime = T(0.3);
  s.add_emitter(source);
  for (int k = 0; k < 60; ++k) s.step(T(1.0 / 120));
  REQUIRE(s.size() > 1000);
  return bits(s);
}

/// A 100 × 100 cloth of springs under gravity, its top row held by a plane
/// it rests on: RK4 evaluates the springs four times a step.
template <class C>
std::vector<unsigned char> cloth(const impulse::task_system* tasks) {
  using T = typename C::scalar;
  const std::uint32_t side = 100;
  particle_system<C, gravity, drag, springs> s{side * side};
  if (tasks) s.set_task_system(*tasks);
  for (std::uint32_t i = 0; i < side; ++i)
    for (std::uint32_t j = 0; j < side; ++j) s.add({T(0.1) * T(i), T(5), T(0.1) * T(j)}, {}, T(1) + T((i + j) % 3));
  auto& list = s.template force<springs>();
  for (std::uint32_t i = 0; i < side; ++i)
    for (std::uint32_t j = 0; j < side; ++j) {
      if (i + 1 < side) list.add(i * side + j, (i + 1) * side + j, T(0.1), T(200), T(0.5));
      if (j + 1 < side) list.add(i * side + j, i * side + j + 1, T(0.1), T(200), T(0.5));
    }
  s.add_plane(plane_collider<T>::half_space({0, 1, 0}, T(-4), T(0.2), T(0.5)));
  for (int k = 0; k < 40; ++k) s.step(T(1.0 / 240));
  return bits(s);
}

/// Eight wheels, each a hub tied to 1 000 particles on a ring and each
/// of those tied to the next. A hub's 1 000 springs' forces are computed
/// in many ranges, by whichever worker, and summed in one.
template <class C>
std::vector<unsigned char> wheels(const impulse::task_system* tasks) {
  using T = typename C::scalar;
  const std::uint32_t count = 8, spokes = 1000;
  particle_system<C, gravity, springs> s{count * (spokes + 1)};
  if (tasks) s.set_task_system(*tasks);
  auto& list = s.template force<springs>();
  for (std::uint32_t w = 0; w < count; ++w) {
    const std::uint32_t hub = s.add({T(5) * T(w), 10, 0}, {0, 0, 1});
    for (std::uint32_t k = 0; k < spokes; ++k) {
      const T angle = T(6.283185307179586) * T(k) / T(spokes);
      s.add({T(5) * T(w) + T(2) * std::cos(angle), T(10), T(2) * std::sin(angle)},
            {-std::sin(angle), 0, std::cos(angle)});
    }
    for (std::uint32_t k = 1; k <= spokes; ++k) {
      list.add(hub, hub + k, T(2.1), T(300), T(0.2));
      list.add(hub + k, hub + k % spokes + 1, T(0.012), T(300), T(0.2));
    }
  }
  for (int k = 0; k < 30; ++k) s.step(T(1.0 / 240));
  return bits(s);
}

template <class T, class I>
using threads_config = particle_test::config<T, particle_test::native<T>, I>;

template <class C, class Scene>
void check_any_worker_count(Scene scene) {
  const std::vector<unsigned char> one = scene(nullptr);
  for (std::uint32_t workers : {1u, 2u, 3u, 8u}) {
    CAPTURE(workers);
    impulse::thread_pool pool{workers};
    const impulse::task_system tasks = pool.tasks();
    CHECK(scene(&tasks) == one);
  }
  const impulse::task_system backwards = backwards_scheduler::tasks();
  CHECK(scene(&backwards) == one);
}

TEST_CASE_TEMPLATE("the particles scene with ageing and an emitter is bit-identical for 1, 2, 3 and 8 workers", C,
                   threads_config<float, in::symplectic_euler>, threads_config<float, in::rk4>,
                   threads_config<double, in::euler>, threads_config<double, in::midpoint>) {
  check_any_worker_count<C>([](const impulse::task_system* t) { return snow<C>(t); });
}

TEST_CASE_TEMPLATE("a cloth of springs is bit-identical for 1, 2, 3 and 8 workers", C,
                   threads_config<float, in::rk4>, threads_config<double, in::symplectic_euler>) {
  check_any_worker_count<C>([](const impulse::task_system* t) { return cloth<C>(t); });
}

TEST_CASE_TEMPLATE("a hub tied to 1 000 springs is bit-identical for 1, 2, 3 and 8 workers", C,
                   threads_config<float, in::rk4>, threads_config<double, in::euler>) {
  check_any_worker_count<C>([](const impulse::task_system* t) { return wheels<C>(t); });
}

/// A chain of 60 000 particles and springs (many ranges of the springs'
/// forces), stepped once; then every seventh spring's far end is moved one
/// particle along, every fifth spring made stiffer and longer, and the
/// chain stepped again, in place or (fresh) in a new system given the same
/// particles and the changed springs. In place, each particle's springs
/// must be listed afresh, or a particle would sum a spring it no longer
/// has, and the changed parameters must be copied, or the old would pull.
template <class C>
std::vector<unsigned char> rewired_chain(const impulse::task_system* tasks, bool fresh) {
  using T = typename C::scalar;
  using chain = particle_system<C, gravity, springs>;
  const std::uint32_t n = 60000;
  chain s{n};
  if (tasks) s.set_task_system(*tasks);
  for (std::uint32_t i = 0; i < n; ++i) s.add({T(0.01) * T(i), T(1) + T(i % 5) * T(0.001), 0}, {});
  auto& list = s.template force<springs>();
  for (std::uint32_t i = 0; i + 1 < n; ++i) list.add(i, i + 1, T(0.01), T(50), T(0.1));
  s.step(T(1.0 / 240));
  for (std::size_t k = 0; k < list.size(); k += 7) {
    spring<T> moved = list[k];
    if (moved.b + 1 < n) ++moved.b;
    list.set(k, moved);
  }
  for (std::size_t k = 0; k < list.size(); k += 5) {
    spring<T> retuned = list[k];
    retuned.stiffness *= 2;
    retuned.rest_length += T(0.003);
    list.set(k, retuned);
  }
  if (!fresh) {
    s.step(T(1.0 / 240));
    return bits(s);
  }
  chain again{n};
  if (tasks) again.set_task_system(*tasks);
  const auto p = s.positions(), v = s.velocities();
  for (std::uint32_t i = 0; i < n; ++i) again.add({p.x[i], p.y[i], p.z[i]}, {v.x[i], v.y[i], v.z[i]});
  again.template force<springs>() = list;
  again.step(T(1.0 / 240));
  return bits(again);
}

TEST_CASE_TEMPLATE("springs rewired and retuned between steps act as in a fresh system, for 1, 2, 3 and 8 workers", C,
                   threads_config<float, in::euler>, threads_config<double, in::rk4>) {
  CHECK(rewired_chain<C>(nullptr, false) == rewired_chain<C>(nullptr, true));
  check_any_worker_count<C>([](const impulse::task_system* t) { return rewired_chain<C>(t, false); });
}

TEST_CASE("the first spring in list order past the particles is the one reported, for 1, 2, 3 and 8 workers") {
  using C = threads_config<float, in::euler>;
  const std::uint32_t n = 60000;
  for (std::uint32_t workers : {1u, 2u, 3u, 8u}) {
    CAPTURE(workers);
    impulse::thread_pool pool{workers};
    particle_system<C, gravity, springs> s{n};
    s.set_task_system(pool.tasks());
    for (std::uint32_t i = 0; i < n; ++i) s.add({float(i), 1, 0}, {});
    auto& list = s.force<springs>();
    for (std::uint32_t i = 0; i + 1 < n; ++i) list.add(i, i + 1, 1.0f, 50.0f);
    list.set(52000, {52000, n + 3, 1.0f, 50.0f, 0.0f});  // no such particle, in the last range
    list.set(41000, {41000, n, 1.0f, 50.0f, 0.0f});      // nor this, in an earlier range
    const std::vector<unsigned char> before = bits(s);
    auto refused_step = [&] {
      impulse::invalid_argument raised(impulse::error_code::none, "");
      try {
        s.step(1.0f / 240);
      } catch (const impulse::invalid_argument& e) {
        raised = e;
      }
      return raised;
    };
    const impulse::invalid_argument first = refused_step();
    CHECK(first.code() == impulse::error_code::out_of_range);
    CHECK(first.object() == 41000);
    list.set(41000, {41000, 41001, 1.0f, 50.0f, 0.0f});
    const impulse::invalid_argument second = refused_step();
    CHECK(second.code() == impulse::error_code::out_of_range);
    CHECK(second.object() == 52000);
    CHECK(bits(s) == before);  // refused before anything moved
    list.set(52000, {52000, 52001, 1.0f, 50.0f, 0.0f});
    s.step(1.0f / 240);
    CHECK(bits(s) != before);
    // As a system that never saw the bad springs: the refused steps left
    // nothing of them behind.
    particle_system<C, gravity, springs> fresh{n};
    fresh.set_task_system(pool.tasks());
    for (std::uint32_t i = 0; i < n; ++i) fresh.add({float(i), 1, 0}, {});
    fresh.force<springs>() = list;
    fresh.step(1.0f / 240);
    CHECK(bits(fresh) == bits(s));
  }
}

TEST_CASE("a task system with one callback or no worker is refused and the old one kept") {
  particle_system<particle_test::config<float, 1>, gravity> s{4};
  impulse::thread_pool pool{2};
  s.set_task_system(pool.tasks());
  impulse::task_system half = pool.tasks();
  half.finish = nullptr;
  CHECK(impulse::test::error_code_of([&] { s.set_task_system(half); }) == impulse::error_code::invalid_parameter);
  impulse::task_system none = pool.tasks();
  none.workers = 0;
  CHECK(impulse::test::error_code_of([&] { s.set_task_system(none); }) == impulse::error_code::invalid_parameter);
  CHECK(s.tasks().workers == 2);
  CHECK(impulse::test::error_code_of([] { impulse::thread_pool empty{0}; }) ==
        impulse::error_code::invalid_parameter);
}

}  // namespace

}  // namespace particles_threads_tests
