// impulse/core/slot_map.hpp — dense storage addressed by stable, checked ids.
//
// Bodies and springs live in dense arrays so that a step runs over
// contiguous memory, and are named by ids that stay valid while the objects
// around them come and go (Box2D's b2BodyId works the same way). An id is a
// slot index and the slot's generation: removing an object bumps its slot's
// generation, so a stale id is recognised and refused instead of silently
// naming whatever took the slot next. Removal moves the last element into
// the hole, so dense positions change; ids do not. A slot is retired
// before its generation wraps, so a destroyed id never names a live object.
//
// A user's ids also carry their owner: the world that made them (a number
// world.hpp draws for each world it constructs). A slot_map refuses an id
// of another owner, so an id kept from one world never names a body of
// another, even at the same slot and generation.
#pragma once

#include <concepts>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <utility>
#include <vector>

#include "error.hpp"

namespace impulse {

namespace detail {
/// The owner of an id that has none: the broad phase's proxies, which
/// never leave their world.
struct no_owner {
  friend constexpr bool operator==(no_owner, no_owner) noexcept = default;
};
}  // namespace detail

/// A stable, checked handle. Tag keeps body and spring ids apart at
/// compile time; Tag::owned says whether the id names its owner too.
template <class Tag>
struct object_id {
  std::uint32_t index = no_object;  ///< slot; no_object for "none"
  std::uint32_t generation = 0;     ///< bumped each time the slot is freed
  /// The world that made it (0: none); costs nothing in an unowned id.
  [[no_unique_address]] std::conditional_t<Tag::owned, std::uint32_t, detail::no_owner> owner{};

  [[nodiscard]] constexpr bool is_none() const noexcept { return index == no_object; }
  friend constexpr bool operator==(const object_id&, const object_id&) = default;
};

/// An id type that names its owner.
template <class Id>
concept owned_id = requires(Id id) {
  { id.owner } -> std::convertible_to<std::uint32_t>;
};

template <class V, class Id>
class slot_map {
  /// The id's generation type: 32 bits for impulse's ids; a test's id with
  /// a narrower one wraps sooner.
  using generation_type = decltype(Id{}.generation);

 public:
  [[nodiscard]] std::size_t size() const noexcept { return values_.size(); }
  [[nodiscard]] bool empty() const noexcept { return values_.empty(); }
  [[nodiscard]] bool contains(Id id) const noexcept {
    if constexpr (owned_id<Id>) {
      if (id.owner != owner_) return false;
    }
    return id.index < slots_.size() && slots_[id.index].generation == id.generation &&
           slots_[id.index].dense != free_slot;
  }

  /// Sets the owner stamped on the ids this map makes and required of the
  /// ids it is given; the ids it holds take the new owner.
  void set_owner(std::uint32_t owner) noexcept
    requires owned_id<Id>
  {
    owner_ = owner;
    for (Id& id : ids_) id.owner = owner;
  }
  /// The id of the live object at `slot` with `generation`, stamped with
  /// this map's owner (for ids stored without it, as proxies' user data).
  [[nodiscard]] Id id_at(std::uint32_t slot, generation_type generation) const noexcept {
    Id id{slot, generation};
    if constexpr (owned_id<Id>) id.owner = owner_;
    return id;
  }

  Id insert(V value) {
    std::uint32_t slot;
    if (free_.empty()) {
      if (slots_.size() >= std::size_t(free_slot))
        detail::report_error(error_code::capacity_exceeded, "slot_map: every 32-bit slot index is in use or retired");
      slot = static_cast<std::uint32_t>(slots_.size());
      slots_.push_back({free_slot, 0});
    } else {
      slot = free_.back();
      free_.pop_back();
    }
    slots_[slot].dense = static_cast<std::uint32_t>(values_.size());
    values_.push_back(std::move(value));
    ids_.push_back(id_at(slot, slots_[slot].generation));
    return ids_.back();
  }

  /// Removes the object; the caller has checked contains(id).
  void erase(Id id) {
    const std::uint32_t dense = slots_[id.index].dense, last = static_cast<std::uint32_t>(values_.size() - 1);
    if (dense != last) {
      values_[dense] = std::move(values_[last]);
      ids_[dense] = ids_[last];
      slots_[ids_[dense].index].dense = dense;
    }
    values_.pop_back();
    ids_.pop_back();
    // A slot whose generation would wrap is retired rather than reused:
    // after 2³² reuses its next id would equal its first, and a stale id
    // kept from then would name the new object. It costs one slot per 2³²
    // removals of the same slot.
    const generation_type next = generation_type(slots_[id.index].generation + 1);
    slots_[id.index] = {free_slot, next};
    if (next != generation_type(0)) free_.push_back(id.index);
  }

  /// Position of a live id in the dense arrays.
  [[nodiscard]] std::size_t dense_index(Id id) const noexcept { return slots_[id.index].dense; }
  [[nodiscard]] V& operator[](Id id) noexcept { return values_[dense_index(id)]; }
  [[nodiscard]] const V& operator[](Id id) const noexcept { return values_[dense_index(id)]; }

  /// The dense arrays: values()[i] is the object whose id is ids()[i].
  [[nodiscard]] std::vector<V>& values() noexcept { return values_; }
  [[nodiscard]] const std::vector<V>& values() const noexcept { return values_; }
  [[nodiscard]] const std::vector<Id>& ids() const noexcept { return ids_; }

 private:
  static constexpr std::uint32_t free_slot = 0xffffffffu;
  struct slot {
    std::uint32_t dense;
    generation_type generation;
  };
  std::vector<V> values_;
  std::vector<Id> ids_;
  std::vector<slot> slots_;
  std::vector<std::uint32_t> free_;
  std::uint32_t owner_ = 0;
};

}  // namespace impulse
