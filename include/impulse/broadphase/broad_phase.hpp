// impulse/broadphase/broad_phase.hpp — what every broad phase provides.
//
// A broad phase keeps proxies (a box and the user's data under a stable
// proxy_id) and answers which pairs of boxes overlap, cheaply enough to run
// every step. The contract, checked by the concept below:
//
//   proxy_id create(const aabb<T>& box, std::uint64_t user_data);
//   void move(proxy_id, const aabb<T>& box);     // the proxy's new box
//   void destroy(proxy_id);
//   void update();                              // brings the pairs up to date
//   pairs(), begun(), ended()                   // spans of proxy_pair, sorted
//   query(const aabb<T>&, callback(proxy_id))   // every proxy whose box overlaps
//   ray_cast(const ray<T>&, T max_fraction, callback(proxy_id, T fraction) -> T)
//   box(proxy_id), user_data(proxy_id), contains(proxy_id), size()
//
// Pairs are as of the last update(): create, move and destroy take effect
// at the next one. A ray-cast callback returns the new max_fraction: the
// fraction it was given to clip the ray at that hit, the old maximum to go
// on, 0 to stop. Bad input (a non-finite or inverted box, a stale id) is
// refused with impulse::invalid_argument and changes nothing.
#pragma once

#include <concepts>
#include <cstdint>
#include <span>

#include "../math/aabb.hpp"
#include "proxy.hpp"

namespace impulse::broadphase {

template <class B, class T>
concept broad_phase = requires(B& b, const B& cb, const aabb<T>& box, proxy_id id, const ray<T>& r) {
  { b.create(box, std::uint64_t{}) } -> std::same_as<proxy_id>;
  b.move(id, box);
  b.destroy(id);
  b.update();
  { cb.pairs() } -> std::convertible_to<std::span<const proxy_pair>>;
  { cb.begun() } -> std::convertible_to<std::span<const proxy_pair>>;
  { cb.ended() } -> std::convertible_to<std::span<const proxy_pair>>;
  cb.query(box, [](proxy_id) {});
  cb.ray_cast(r, T(1), [](proxy_id, T fraction) { return fraction; });
  { cb.box(id) } -> std::convertible_to<aabb<T>>;
  { cb.user_data(id) } -> std::convertible_to<std::uint64_t>;
  { cb.contains(id) } -> std::same_as<bool>;
  { cb.size() } -> std::convertible_to<std::size_t>;
};

}  // namespace impulse::broadphase
