// impulse/broadphase/detail/proxy_store.hpp — the proxies themselves, checked.
//
// Every broad phase keeps its proxies' boxes and user data here, in dense
// arrays under stable ids (core/slot_map.hpp), and refuses bad input at the
// door: a box that is not finite or whose lower corner is above its upper
// one (zero size is fine: a point is a box), or an id that names no proxy.
#pragma once

#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "../../core/error.hpp"
#include "../../core/slot_map.hpp"
#include "../../math/aabb.hpp"
#include "../proxy.hpp"

namespace impulse::broadphase::detail {

template <scalar_type T>
struct proxy {
  aabb<T> box;
  std::uint64_t user_data;
};

template <scalar_type T>
class proxy_store {
 public:
  proxy_id insert(const aabb<T>& box, std::uint64_t user_data) {
    require_box(box);
    changed_ = true;
    return proxies_.insert({box, user_data});
  }
  void set_box(proxy_id id, const aabb<T>& box) {
    require(id);
    require_box(box);
    proxies_[id].box = box;
    changed_ = true;
  }
  /// Stores a box that the caller has found valid (valid_box) for a proxy
  /// it has found here, and leaves take_changed() alone: calls for
  /// distinct proxies may run at once. mark_changed() then tells the
  /// next update.
  void place(proxy_id id, const aabb<T>& box) noexcept { proxies_[id].box = box; }
  void mark_changed() noexcept { changed_ = true; }
  void erase(proxy_id id) {
    require(id);
    proxies_.erase(id);
    changed_ = true;
  }

  void require(proxy_id id) const {
    if (!proxies_.contains(id))
      impulse::detail::report_error(error_code::out_of_range, "broad phase: the id names no proxy", id.index);
  }
  /// Whether require_box() would take the box.
  [[nodiscard]] static bool valid_box(const aabb<T>& box) noexcept {
    return is_finite(box.lower) && is_finite(box.upper) && is_valid(box);
  }
  static void require_box(const aabb<T>& box) {
    if (!is_finite(box.lower) || !is_finite(box.upper))
      impulse::detail::report_error(error_code::non_finite, "broad phase: the box is not finite");
    if (!is_valid(box))
      impulse::detail::report_error(error_code::invalid_parameter,
                                    "broad phase: the box's lower corner is above its upper corner");
  }

  /// Whether a proxy came, moved or went since the last call. A broad
  /// phase whose proxies all stood still has the pairs it had: with every
  /// body asleep, its update costs nothing.
  [[nodiscard]] bool take_changed() noexcept { return std::exchange(changed_, false); }

  [[nodiscard]] bool contains(proxy_id id) const noexcept { return proxies_.contains(id); }
  [[nodiscard]] const aabb<T>& box(proxy_id id) const {
    require(id);
    return proxies_[id].box;
  }
  [[nodiscard]] std::uint64_t user_data(proxy_id id) const {
    require(id);
    return proxies_[id].user_data;
  }
  [[nodiscard]] std::size_t size() const noexcept { return proxies_.size(); }
  [[nodiscard]] std::size_t dense_index(proxy_id id) const noexcept { return proxies_.dense_index(id); }
  [[nodiscard]] const std::vector<proxy<T>>& values() const noexcept { return proxies_.values(); }
  [[nodiscard]] const std::vector<proxy_id>& ids() const noexcept { return proxies_.ids(); }

 private:
  slot_map<proxy<T>, proxy_id> proxies_;
  bool changed_ = false;
};

}  // namespace impulse::broadphase::detail
