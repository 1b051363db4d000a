// impulse/broadphase/brute_force.hpp — every pair tested, every step.
//
// The O(n²) baseline: correct by inspection, so every other broad phase is
// tested against it, and fast enough for a few dozen bodies, where the
// bookkeeping of the others costs more than the tests it saves.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "../core/policy.hpp"
#include "../math/aabb.hpp"
#include "detail/pair_tracker.hpp"
#include "proxy.hpp"
#include "detail/proxy_store.hpp"

namespace impulse::broadphase {

template <scalar_type T>
class basic_brute_force {
 public:
  proxy_id create(const aabb<T>& box, std::uint64_t user_data) { return store_.insert(box, user_data); }
  void move(proxy_id id, const aabb<T>& box) { store_.set_box(id, box); }
  void destroy(proxy_id id) { store_.erase(id); }

  void update() {
    if (!store_.take_changed()) return pairs_.keep();  // nothing came, moved or went
    found_.clear();
    const auto& proxies = store_.values();
    const auto& ids = store_.ids();
    for (std::size_t i = 0; i < proxies.size(); ++i)
      for (std::size_t j = i + 1; j < proxies.size(); ++j)
        if (overlaps(proxies[i].box, proxies[j].box)) found_.push_back(pair_of(ids[i], ids[j]));
    pairs_.publish(found_);
  }

  [[nodiscard]] std::span<const proxy_pair> pairs() const noexcept { return pairs_.pairs(); }
  [[nodiscard]] std::span<const proxy_pair> begun() const noexcept { return pairs_.begun(); }
  [[nodiscard]] std::span<const proxy_pair> ended() const noexcept { return pairs_.ended(); }

  template <class Callback>
  void query(const aabb<T>& box, Callback&& callback) const {
    detail::proxy_store<T>::require_box(box);
    for (std::size_t i = 0; i < store_.size(); ++i)
      if (overlaps(store_.values()[i].box, box)) callback(store_.ids()[i]);
  }

  template <class Callback>
  void ray_cast(const ray<T>& r, T max_fraction, Callback&& callback) const {
    detail::require_ray(r, max_fraction);
    for (std::size_t i = 0; i < store_.size() && max_fraction > T(0); ++i)
      if (const auto t = ray_enters(r, max_fraction, store_.values()[i].box))
        max_fraction = callback(store_.ids()[i], *t);
  }

  [[nodiscard]] const aabb<T>& box(proxy_id id) const { return store_.box(id); }
  [[nodiscard]] std::uint64_t user_data(proxy_id id) const { return store_.user_data(id); }
  [[nodiscard]] bool contains(proxy_id id) const noexcept { return store_.contains(id); }
  [[nodiscard]] std::size_t size() const noexcept { return store_.size(); }

 private:
  detail::proxy_store<T> store_;
  detail::pair_tracker pairs_;
  std::vector<proxy_pair> found_;
};

/// The brute-force policy, for a config's `broadphase`.
struct brute_force {
  static constexpr policy_kind kind = policy_kind::broadphase;
  template <scalar_type T>
  using type = basic_brute_force<T>;
};

}  // namespace impulse::broadphase
