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
// at the next one. Queries and ray casts are for after an update too: a box
// moved or created since may be seen at its old place or not at all (brute
// force sees the new one, the structures their last update's), but a
// destroyed proxy is never reported. Pairs are exact (the boxes themselves
// overlap, not fattened copies), and both the whole set and the changes are
// reported: the narrow phase needs every touching pair each step, contact
// events need the changes (pair_tracker.hpp). A ray-cast callback returns
// the new max_fraction: the fraction it was given to clip the ray at that
// hit, the old maximum to go on, 0 to stop. Bad input (a non-finite or
// inverted box, a stale id) is refused with impulse::invalid_argument and
// changes nothing.
#pragma once

#include <concepts>
#include <cstddef>
#include <cstdint>
#include <span>

#include "../core/policy.hpp"
#include "../math/aabb.hpp"
#include "proxy.hpp"

namespace impulse::broadphase {

// One requirement per member, so that the loud check below can name the
// one that is missing.
namespace detail {
template <class B, class T>
concept has_create = requires(B& b, const aabb<T>& box) {
  { b.create(box, std::uint64_t{}) } -> std::same_as<proxy_id>;
};
template <class B, class T>
concept has_move_destroy_update = requires(B& b, const aabb<T>& box, proxy_id id) {
  b.move(id, box);
  b.destroy(id);
  b.update();
};
template <class B>
concept has_pair_lists = requires(const B& b) {
  { b.pairs() } -> std::convertible_to<std::span<const proxy_pair>>;
  { b.begun() } -> std::convertible_to<std::span<const proxy_pair>>;
  { b.ended() } -> std::convertible_to<std::span<const proxy_pair>>;
};
template <class B, class T>
concept has_query = requires(const B& b, const aabb<T>& box) { b.query(box, [](proxy_id) {}); };
template <class B, class T>
concept has_ray_cast = requires(const B& b, const ray<T>& r) {
  b.ray_cast(r, T(1), [](proxy_id, T fraction) { return fraction; });
};
template <class B, class T>
concept has_accessors = requires(const B& b, proxy_id id) {
  { b.box(id) } -> std::convertible_to<aabb<T>>;
  { b.user_data(id) } -> std::convertible_to<std::uint64_t>;
  { b.contains(id) } -> std::same_as<bool>;
  { b.size() } -> std::convertible_to<std::size_t>;
};
}  // namespace detail

/// Quiet form: true when B is a broad phase over boxes of scalar T.
template <class B, class T>
concept broad_phase = std::default_initializable<B> && detail::has_create<B, T> &&
                      detail::has_move_destroy_update<B, T> && detail::has_pair_lists<B> &&
                      detail::has_query<B, T> && detail::has_ray_cast<B, T> && detail::has_accessors<B, T>;

/// Loud form: `static_assert(check_broad_phase<B, T>());` fails with one
/// message per missing member, naming it.
template <class B, class T>
consteval bool check_broad_phase() {
  static_assert(std::default_initializable<B>, "impulse broad phase: must be default constructible");
  static_assert(detail::has_create<B, T>,
                "impulse broad phase: missing `proxy_id create(const aabb<T>&, std::uint64_t user_data)`");
  static_assert(detail::has_move_destroy_update<B, T>,
                "impulse broad phase: missing `move(proxy_id, const aabb<T>&)`, `destroy(proxy_id)` or `update()`");
  static_assert(detail::has_pair_lists<B>,
                "impulse broad phase: missing `pairs()`, `begun()` or `ended()` (spans of proxy_pair)");
  static_assert(detail::has_query<B, T>, "impulse broad phase: missing `query(const aabb<T>&, callback(proxy_id))`");
  static_assert(detail::has_ray_cast<B, T>,
                "impulse broad phase: missing `ray_cast(const ray<T>&, T max_fraction, callback(proxy_id, T) -> T)`");
  static_assert(detail::has_accessors<B, T>,
                "impulse broad phase: missing `box(id)`, `user_data(id)`, `contains(id)` or `size()`");
  return broad_phase<B, T>;
}

}  // namespace impulse::broadphase
