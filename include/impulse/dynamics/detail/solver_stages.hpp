// impulse/dynamics/detail/solver_stages.hpp — the contact solvers' loops,
// spread over the workers of a task hook (core/task_system.hpp).
//
// A solver runs its whole solve as one program of a stage_runner
// (core/detail/stage_runner.hpp): one call of the hook a step, however
// many loops. Its loops go over batches color by color (the batches of one
// color share no moving body, constraint_graph.hpp), over all batches, or
// over bodies; each item is written by one block only, so the bodies come
// out the same, bit for bit, for any worker count.
//
// The loops hand f a range to loop over, not one item at a time: called
// once per batch, the solver's lambdas stayed out of line and their
// batch's velocities went through memory (pile 7 % slower).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <type_traits>
#include <vector>

#include "../../core/detail/stage_runner.hpp"
#include "../../core/task_system.hpp"
#include "constraint_graph.hpp"
#include "contact_batch.hpp"
#include "contact_rows.hpp"

namespace impulse::detail {

/// Places each batch's rows one after another: first_rows[k] is batch
/// k's first row (load_batch); returns how many rows there are. Worked out
/// before the batches load side by side.
template <scalar_type T>
std::uint32_t place_batch_rows(const constraint_graph& graph, std::span<const contact_constraint<T>> contacts,
                               std::vector<std::uint32_t>& first_rows) {
  first_rows.resize(graph.batch_count());
  std::uint32_t rows = 0;
  for (std::size_t k = 0; k < first_rows.size(); ++k) {
    first_rows[k] = rows;
    rows += std::uint32_t(rows_needed(contacts, graph.batch(k)));
  }
  return rows;
}

class solver_stages {
 public:
  /// Batches, bodies and contacts a worker takes at a time, at the least:
  /// a batch's sweep costs about as much as a few dozen bodies' moves.
  static constexpr std::uint32_t min_batches = 8, min_bodies = 256, min_contacts = 128;

  void set_task_system(const task_system& tasks) noexcept { tasks_ = tasks; }
  [[nodiscard]] const task_system& tasks() const noexcept { return tasks_; }

  /// Whether the loops are shared with other workers: inside run(), with
  /// a hook that has them.
  [[nodiscard]] bool shared() const noexcept { return runner_.shared(); }

  /// Runs program() on this thread, its loops shared with the workers.
  template <class Program>
  void run(Program& program) {
    runner_.run(tasks_, program);
  }

  /// f(written, range, backward) over the batches, color after color,
  /// each color's batches split in ranges across the workers (a stage
  /// each); `written` says which lanes scatter may write (contact_batch.hpp,
  /// lanes_written), a constant. When `backward`, the colors go last to
  /// first and f walks each range back. On one thread, f gets every batch
  /// at once.
  template <class Batch, class F>
  void by_color(const constraint_graph& graph, std::span<Batch> batches, bool backward, F& f) {
    using lanes = lanes_written;
    if (!runner_.shared()) {
      f(std::integral_constant<lanes, lanes::every>{}, batches, backward);
      return;
    }
    const std::size_t colors = graph.color_count();
    for (std::size_t i = 0; i < colors; ++i) {
      const std::size_t q = backward ? colors - 1 - i : i;
      const std::uint32_t first = graph.first_batch(q), count = graph.first_batch(q + 1) - first;
      auto range = [&](std::uint32_t begin, std::uint32_t end) {
        f(std::integral_constant<lanes, lanes::moving>{}, batches.subspan(first + begin, end - begin), backward);
      };
      runner_.loop(count, min_batches, range);
    }
  }

  /// f(range) over the batches in ranges, in any order: f reads and
  /// writes only its batches' own.
  template <class Batch, class F>
  void each_batch(std::span<Batch> batches, F& f) {
    auto range = [&](std::uint32_t begin, std::uint32_t end) { f(batches.subspan(begin, end - begin)); };
    runner_.loop(std::uint32_t(batches.size()), min_batches, range);
  }

  /// f(begin, end) over [0, count) in ranges of at least `least`, in any
  /// order: f touches only its items' own.
  template <class F>
  void each_index(std::size_t count, std::uint32_t least, F& f) {
    auto range = [&](std::uint32_t begin, std::uint32_t end) { f(std::size_t(begin), std::size_t(end)); };
    runner_.loop(std::uint32_t(count), least, range);
  }

  /// prepare_contacts across the workers, as one hook call of its own.
  template <scalar_type T>
  void prepare(std::span<const solver_body<T>> bodies, std::span<contact_constraint<T>> contacts) const noexcept {
    auto range = [&](std::uint32_t begin, std::uint32_t end, std::uint32_t) {
      prepare_contacts(bodies, contacts.subspan(begin, end - begin));
    };
    parallel_for(tasks_, std::uint32_t(contacts.size()), min_contacts, range);
  }

 private:
  task_system tasks_{};
  stage_runner runner_;
};

}  // namespace impulse::detail
