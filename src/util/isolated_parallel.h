// Runs a parallel computation so that it always completes: its TBB loops get a task-group
// context with no parent, so the cancellation of an enclosing task group (for example a
// sweep job that failed beside this one) cannot cut them short and leave half-built data.
// Exceptions thrown inside still reach the caller.
#pragma once

#include <tbb/task_group.h>

#include <optional>
#include <utility>

namespace contactlab {

template <typename F>
auto RunIsolatedFromCancellation(F&& f) -> decltype(f()) {
  tbb::task_group_context context(tbb::task_group_context::isolated);
  tbb::task_group group(context);
  std::optional<decltype(f())> result;
  group.run_and_wait([&] { result.emplace(f()); });
  return std::move(*result);
}

}  // namespace contactlab
