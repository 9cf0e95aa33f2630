// Stations off the transom turns: where an open transom's edge turns back in x (DTMB 5415's bilge
// corner) is found from the boundary runs, not at a run's end, not on a step standing at one x,
// not on other boundary kinds; stations near a turn move off it to 0.4 of their spacing, on the
// side they were on, and borders stay.
#include <gtest/gtest.h>

#include <vector>

#include "structured/structured_steps.h"

namespace hm::structured {
namespace {

// One boundary run through the given points, of the given kind.
struct RunCase {
  SurfaceMesh surface;
  FeatureSet features;
};
RunCase run_through(std::vector<Vec3d> points, BoundaryKind kind) {
  RunCase c;
  c.surface.positions = std::move(points);
  BoundaryRun run;
  run.kind = kind;
  for (std::size_t i = 0; i < c.surface.positions.size(); ++i)
    run.vertices.push_back(static_cast<Index>(i));
  c.features.boundaries.push_back(run);
  return c;
}

TEST(PlanStations, ATransomEdgeTurnsWhereItRunsBackInX) {
  // DTMB 5415's transom edge (m): from the keel forward and out to the bilge corner, then aft
  // and up to the deck.
  const std::vector<Vec3d> edge{{3.050, 0, 0.075},
                                {3.040, 0.12, 0.085},
                                {3.030, 0.224, 0.112},
                                {3.045, 0.26, 0.2},
                                {3.060, 0.28, 0.296}};
  const RunCase dtmb = run_through(edge, BoundaryKind::kTransomEdge);
  const std::vector<TransomTurn> turns = transom_turns(dtmb.surface, dtmb.features, 0.05);
  ASSERT_EQ(turns.size(), 1u);
  EXPECT_DOUBLE_EQ(turns[0].x, 3.030);
  EXPECT_EQ(turns[0].side, +1);
  // With panels of 0.2 m both branches must run 0.04 m; the keel's runs 0.02 m: no turn.
  EXPECT_EQ(transom_turns(dtmb.surface, dtmb.features, 0.2).size(), 0u);
  // The same points as a deck edge: no transom, no turn.
  const RunCase deck = run_through(edge, BoundaryKind::kDeckEdge);
  EXPECT_TRUE(transom_turns(deck.surface, deck.features, 0.05).empty());
  // A step standing at one x (a forecastle break): its least x is anywhere along it.
  const RunCase step =
      run_through({{-48.5, 0, 5}, {-48.5 - 1e-6, 2, 5.5}, {-48.5, 4, 6}, {-48.5 + 1e-6, 6, 6.5}},
                  BoundaryKind::kTransomEdge);
  EXPECT_TRUE(transom_turns(step.surface, step.features, 1.0).empty());
  // A run whose least x is at one of its ends turns nowhere.
  const RunCase plain =
      run_through({{3.0, 0, 0}, {3.02, 0.1, 0.1}, {3.05, 0.2, 0.3}}, BoundaryKind::kTransomEdge);
  EXPECT_TRUE(transom_turns(plain.surface, plain.features, 0.05).empty());
}

TEST(PlanStations, StationsKeepClearOfTurnsAndBordersStay) {
  StationPlan plan;
  plan.x = {0, 1, 2, 3, 4, 5};
  plan.border = {1, 0, 0, 0, 1, 1};
  const std::vector<TransomTurn> turns{
      {1.05, +1},  // station 1 just on the whole side: to 1.05 - 0.4
      {2.9, +1},   // station 3 just on the split side: to 2.9 + 0.4
      {4.02, -1},  // station 4 is a border: stays
  };
  keep_clear_of_turns(turns, plan);
  EXPECT_DOUBLE_EQ(plan.x[1], 0.65);
  EXPECT_DOUBLE_EQ(plan.x[2], 2.0);
  EXPECT_DOUBLE_EQ(plan.x[3], 3.3);
  EXPECT_DOUBLE_EQ(plan.x[4], 4.0);
  EXPECT_TRUE(std::is_sorted(plan.x.begin(), plan.x.end()));
  // Side -1: the hull is in two at smaller x; a station just there moves further down.
  StationPlan fore;
  fore.x = {0, 1, 2, 3};
  fore.border = {1, 0, 0, 1};
  keep_clear_of_turns(std::vector<TransomTurn>{{2.1, -1}}, fore);
  EXPECT_DOUBLE_EQ(fore.x[2], 2.1 - 0.4);
  EXPECT_DOUBLE_EQ(fore.x[1], 1.0);
}

}  // namespace
}  // namespace hm::structured
