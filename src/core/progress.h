// Progress and cancellation for long work. The CLI draws bars; tests pass a silent one.
#pragma once

#include <atomic>
#include <string_view>

namespace hm {

class Progress {
 public:
  virtual ~Progress() = default;
  // A named stage begins (for example "tessellate").
  virtual void stage(std::string_view name) {}
  // Fraction of the current stage done, in [0, 1]. Called from one thread at a time.
  virtual void update(double fraction) {}
  // Long loops poll this and stop early by throwing CancelledError.
  bool cancelled() const { return cancelled_.load(std::memory_order_relaxed); }
  void cancel() { cancelled_.store(true, std::memory_order_relaxed); }

 private:
  std::atomic<bool> cancelled_{false};
};

// Discards everything; the default for library calls and tests.
inline Progress& silent_progress() {
  thread_local Progress p;
  return p;
}

}  // namespace hm
