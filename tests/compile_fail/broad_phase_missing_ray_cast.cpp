// expect: impulse broad phase: missing `ray_cast
// A broad phase without ray casts is named for what it lacks.
#include <cstdint>
#include <span>

#include "impulse/broadphase/broad_phase.hpp"

class no_rays {
 public:
  impulse::proxy_id create(const impulse::aabb<float>&, std::uint64_t) { return {}; }
  void move(impulse::proxy_id, const impulse::aabb<float>&) {}
  void destroy(impulse::proxy_id) {}
  void update() {}
  std::span<const impulse::proxy_pair> pairs() const { return {}; }
  std::span<const impulse::proxy_pair> begun() const { return {}; }
  std::span<const impulse::proxy_pair> ended() const { return {}; }
  template <class F> void query(const impulse::aabb<float>&, F&&) const {}
  impulse::aabb<float> box(impulse::proxy_id) const { return {}; }
  std::uint64_t user_data(impulse::proxy_id) const { return 0; }
  bool contains(impulse::proxy_id) const { return false; }
  std::size_t size() const { return 0; }
};

static_assert(impulse::broadphase::check_broad_phase<no_rays, float>());
