// Peak heap memory per benchmark, for the ladders' reports: every bench executable links this
// file, which replaces the global operator new and delete to count the bytes live and hands
// Google Benchmark their peak between its Start and Stop. The library then runs each benchmark
// once more with the counter on and reports `max_bytes_used` (bytes) and `allocs_per_iter` in
// its JSON and console output. Counted: what C++ allocates (containers, meshes, our BVH arrays).
// Not counted: memory Embree or TBB take from malloc or mmap directly.
#include <benchmark/benchmark.h>
#include <malloc.h>

#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <new>

namespace {

std::atomic<std::int64_t> g_live{0}, g_peak{0}, g_allocs{0};

void* counted(void* p) {
  if (!p) throw std::bad_alloc();
  const auto n = static_cast<std::int64_t>(malloc_usable_size(p));
  const std::int64_t live = g_live.fetch_add(n, std::memory_order_relaxed) + n;
  std::int64_t peak = g_peak.load(std::memory_order_relaxed);
  while (live > peak && !g_peak.compare_exchange_weak(peak, live, std::memory_order_relaxed)) {
  }
  g_allocs.fetch_add(1, std::memory_order_relaxed);
  return p;
}

void uncounted(void* p) {
  if (!p) return;
  g_live.fetch_sub(static_cast<std::int64_t>(malloc_usable_size(p)), std::memory_order_relaxed);
  std::free(p);
}

class PeakHeap : public benchmark::MemoryManager {
 public:
  void Start() override {
    allocs0_ = g_allocs.load();
    g_peak.store(g_live.load());
    live0_ = g_live.load();
  }
  void Stop(Result& r) override {
    r.num_allocs = g_allocs.load() - allocs0_;
    r.max_bytes_used = g_peak.load() - live0_;  // above what was live at the start
  }
  void Stop(Result* r) override { Stop(*r); }

 private:
  std::int64_t allocs0_ = 0, live0_ = 0;
};

PeakHeap g_manager;
const bool g_registered = [] {
  benchmark::RegisterMemoryManager(&g_manager);
  return true;
}();

}  // namespace

void* operator new(std::size_t n) { return counted(std::malloc(n ? n : 1)); }
void* operator new(std::size_t n, std::align_val_t a) {
  const auto al = static_cast<std::size_t>(a);
  return counted(std::aligned_alloc(al, (n + al - 1) / al * al));
}
void operator delete(void* p) noexcept { uncounted(p); }
void operator delete(void* p, std::size_t) noexcept { uncounted(p); }
void operator delete(void* p, std::align_val_t) noexcept { uncounted(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { uncounted(p); }
