// A per-entity work budget: shared sub-entities (a 102 composite whose members are composites
// that repeat each other, thousands of edges referencing one big curve) could otherwise make a
// small hostile file expand exponentially or run for hours. Each top-level conversion (one patch)
// runs on one thread and opens a BudgetScope; the converters draw from it.
#pragma once

#include <cstdint>

namespace hm::iges {

struct WorkBudget {
  std::uint64_t curve_units = 0;  // control points (+ overhead) produced by curve conversions
  std::uint64_t projections = 0;  // closest-point projections for trim curves
};

// A curve costs its control points plus kCurveOverhead (its own bookkeeping).
inline constexpr std::uint64_t kCurveOverhead = 16;
inline std::uint64_t max_curve_units(std::uint64_t max_control_points) {
  return 2 * max_control_points + 1'000'000;
}
inline constexpr std::uint64_t kMaxProjectionsPerEntity = 400'000;

inline WorkBudget& job_budget() {
  thread_local WorkBudget b;
  return b;
}

class BudgetScope {
 public:
  BudgetScope() { job_budget() = WorkBudget{}; }
  BudgetScope(const BudgetScope&) = delete;
  BudgetScope& operator=(const BudgetScope&) = delete;
};

}  // namespace hm::iges
