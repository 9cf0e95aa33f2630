// The one thin parallel layer. Stages call these, never raw TBB. Each index writes its own slot,
// so results do not depend on the thread count; small inputs run serially (no task overhead).
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>
#include <tbb/task_group.h>

#include <algorithm>
#include <cstddef>
#include <exception>
#include <mutex>
#include <utility>

namespace hm {

// Below this many items a loop runs on the calling thread.
inline constexpr std::size_t kSerialCutoff = 256;

// Calls f(i) for every i in [begin, end). f must write only state owned by index i. An exception
// thrown by f is carried out of the task and rethrown on the calling thread (first one wins).
// Loops of fewer than serial_below items run serially: raise it for loops that run many times
// on light items, where waking the workers costs more than the work (and a host that steals a
// vCPU turns every wake-up into a wait).
template <class F>
void parallel_for(std::size_t begin, std::size_t end, F&& f, std::size_t grain = 64,
                  std::size_t serial_below = kSerialCutoff) {
  if (end <= begin) return;
  if (end - begin < std::max(serial_below, std::size_t{1})) {
    for (std::size_t i = begin; i < end; ++i) f(i);
    return;
  }
  std::exception_ptr error;
  std::once_flag once;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(begin, end, grain),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      try {
                        for (std::size_t i = r.begin(); i != r.end(); ++i) f(i);
                      } catch (...) {
                        std::call_once(once, [&] { error = std::current_exception(); });
                      }
                    });
  if (error) std::rethrow_exception(error);
}

// Same, with a per-index cost so that a few heavy items (large patches) spread over threads.
template <class F>
void parallel_for_each_item(std::size_t count, F&& f) {
  if (count == 0) return;
  if (count == 1) {
    f(std::size_t{0});
    return;
  }
  std::exception_ptr error;
  std::once_flag once;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 1),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      try {
                        for (std::size_t i = r.begin(); i != r.end(); ++i) f(i);
                      } catch (...) {
                        std::call_once(once, [&] { error = std::current_exception(); });
                      }
                    });
  if (error) std::rethrow_exception(error);
}

// Sorts [first, last) by `less`, in parallel above the serial cut-off. Equal elements may end in
// any order, so `less` must be a strict total order on the values present (break ties by index)
// for the result to be thread-count independent.
template <class It, class Less>
void parallel_sort(It first, It last, Less less) {
  if (static_cast<std::size_t>(last - first) < 16 * kSerialCutoff) {
    std::sort(first, last, less);
  } else {
    tbb::parallel_sort(first, last, less);
  }
}

// Runs f on a task of its own beside the caller's work, for a result the caller needs only later
// and whose inputs stay untouched meanwhile (a report's reference figures). wait() joins it and
// rethrows what f threw; the destructor joins it too, and swallows that. With one thread, f runs
// when the caller waits (or helps with its own loops).
class BackgroundTask {
 public:
  template <class F>
  explicit BackgroundTask(F&& f) {
    group_.run([this, f = std::forward<F>(f)] {
      try {
        f();
      } catch (...) {
        error_ = std::current_exception();
      }
    });
  }
  BackgroundTask(const BackgroundTask&) = delete;
  BackgroundTask& operator=(const BackgroundTask&) = delete;
  ~BackgroundTask() { group_.wait(); }
  void wait() {
    group_.wait();
    if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
  }

 private:
  tbb::task_group group_;
  std::exception_ptr error_;
};

}  // namespace hm
