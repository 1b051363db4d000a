// impulse/world/detail/shape_store.hpp — the shapes of a world's bodies, one array
// per shape type of the config's shape_list.
//
// A body names its shape by a handle (the type's place in the list and a
// slot in that type's array) rather than a pointer, so that a world is a
// plain value: copying it (a snapshot) copies the shapes and every handle
// stays right. visit() turns a handle back into the shape, by a chain of
// comparisons as long as the list (six at most), for the few places that
// need the type: bounds, ray casts, drawing. The narrow phase goes through
// the dispatcher's table with the address instead.
#pragma once

#include <cstddef>
#include <cstdint>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include "../../core/policy.hpp"

namespace impulse::detail {

struct shape_handle {
  std::uint32_t type = 0;  ///< place of the shape's type in the shape_list
  std::uint32_t slot = 0;  ///< place in that type's array
};

template <class List, scalar_type T>
class shape_store;

template <template <class> class... Shapes, scalar_type T>
class shape_store<shape_list<Shapes...>, T> {
  template <class S>
  struct column {
    std::vector<S> items;
    std::vector<std::uint32_t> free;
  };
  static constexpr std::size_t count = sizeof...(Shapes);

 public:
  template <class S>
  static constexpr std::uint32_t index_of() noexcept {
    constexpr bool same[] = {std::is_same_v<S, Shapes<T>>..., false};
    for (std::uint32_t i = 0; i < count; ++i)
      if (same[i]) return i;
    return std::uint32_t(count);
  }

  template <class S>
  shape_handle add(const S& shape) {
    constexpr std::uint32_t type = index_of<S>();
    column<S>& c = std::get<type>(columns_);
    if (c.free.empty()) {
      c.items.push_back(shape);
      return {type, std::uint32_t(c.items.size() - 1)};
    }
    const std::uint32_t slot = c.free.back();
    c.free.pop_back();
    c.items[slot] = shape;
    return {type, slot};
  }

  void remove(shape_handle h) {
    // The shape stays in its slot until the slot is reused: hulls and
    // meshes have no empty state to put there.
    visit_column(h, [&](auto& c) { c.free.push_back(h.slot); });
  }

  [[nodiscard]] const void* address(shape_handle h) const noexcept {
    const void* p = nullptr;
    visit(h, [&](const auto& shape) { p = &shape; });
    return p;
  }

  /// f(shape) for the shape h names.
  template <class F, std::size_t I = 0>
  decltype(auto) visit(shape_handle h, F&& f) const {
    if constexpr (I + 1 == count) {
      return f(std::get<I>(columns_).items[h.slot]);
    } else {
      if (h.type == I) return f(std::get<I>(columns_).items[h.slot]);
      return visit<F, I + 1>(h, std::forward<F>(f));
    }
  }

 private:
  template <class F, std::size_t I = 0>
  void visit_column(shape_handle h, F&& f) {
    if constexpr (I < count) {
      if (h.type == I) return f(std::get<I>(columns_));
      visit_column<F, I + 1>(h, std::forward<F>(f));
    }
  }

  std::tuple<column<Shapes<T>>...> columns_;
};

}  // namespace impulse::detail
