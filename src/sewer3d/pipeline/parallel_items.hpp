#pragma once
/// \file
/// Runs a stage's per-item work (one acquisition at a time per worker) on `threads` workers,
/// each with its own state built on first use, reporting progress from one thread at a time.

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstddef>
#include <functional>
#include <mutex>

namespace sewer3d {

/// `threads`, capped at what TBB allows (the machine's cores): more would only make TBB print a
/// warning when an arena of that size is made.
inline int AllowedThreads(int threads) {
  const auto allowed =
      tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
  return static_cast<int>(std::min<std::size_t>(std::max(threads, 1), allowed));
}

/// Calls `work(i, state)` for every i in [0, count) on `threads` workers; `make_state()` builds
/// one State per worker. `done(finished)` is called after each item, never from two threads at
/// once. Each worker holds one item at a time (the arena isolates nested parallelism).
template <typename State, typename MakeState, typename Work>
void ForEachItem(std::size_t count, int threads, MakeState make_state, Work work,
                 const std::function<void(int finished)>& done) {
  std::mutex mutex;
  int finished = 0;
  auto one = [&](std::size_t i, State& state) {
    work(i, state);
    const std::lock_guard lock(mutex);
    ++finished;
    if (done) done(finished);
  };
  if (threads == 1) {
    State state = make_state();
    for (std::size_t i = 0; i < count; ++i) one(i, state);
    return;
  }
  tbb::enumerable_thread_specific<State> per_worker(make_state);
  tbb::task_arena arena(AllowedThreads(threads));
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 1),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        for (std::size_t i = range.begin(); i != range.end(); ++i) {
                          // Isolated: a worker waiting inside an item's own parallel loops
                          // never takes another item, so it holds one item's images.
                          tbb::this_task_arena::isolate([&] { one(i, per_worker.local()); });
                        }
                      });
  });
}

}  // namespace sewer3d
