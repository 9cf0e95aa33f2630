// Stations off the boundary's turns: where an open transom's edge turns back in x (DTMB 5415's
// bilge corner) is found from the boundary runs, not at a run's end, not on a step standing at
// one x, not on other boundary kinds; so are the turns of the centre-plane profile (a stem's
// notch above a sonar dome); stations near a turn move off it to its share of their spacing, on
// the side they were on, and borders stay.
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
  const std::vector<BoundaryTurn> turns = transom_turns(dtmb.surface, dtmb.features, 0.05);
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
  const std::vector<BoundaryTurn> turns{
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
  keep_clear_of_turns(std::vector<BoundaryTurn>{{2.1, -1}}, fore);
  EXPECT_DOUBLE_EQ(fore.x[2], 2.1 - 0.4);
  EXPECT_DOUBLE_EQ(fore.x[1], 1.0);
  // A turn's own clearance: a profile turn's 0.1 moves only the station within a tenth.
  StationPlan near;
  near.x = {0, 1, 2, 3};
  near.border = {1, 0, 0, 1};
  keep_clear_of_turns(std::vector<BoundaryTurn>{{1.95, -1, 0.1}, {0.8, +1, 0.1}}, near);
  EXPECT_DOUBLE_EQ(near.x[2], 1.95 + 0.1);
  EXPECT_DOUBLE_EQ(near.x[1], 1.0);
}

// DTMB 5415's centre-plane profile near its bow (m), from the deck down: the stem runs aft to a
// notch at x = -2.631 above the sonar dome, the dome's nose runs forward to x = -2.665, and the
// keel runs aft. A station just forward of the notch cuts the stem and the dome apart; one just
// aft passes the notch within a hair.
std::vector<Vec3d> dtmb_profile() {
  return {{-3.026, 0, 0.45},  {-2.8, 0, 0.2},     {-2.6425, 0, 0.0}, {-2.633, 0, -0.05},
          {-2.631, 0, -0.08}, {-2.634, 0, -0.11}, {-2.65, 0, -0.15}, {-2.665, 0, -0.19},
          {-2.64, 0, -0.22},  {-2.5, 0, -0.23},   {-2.0, 0, -0.15},  {0.0, 0, -0.15}};
}

TEST(PlanStations, AStemsNotchAboveADomeIsAProfileTurn) {
  const std::vector<BoundaryTurn> turns = profile_turns(dtmb_profile(), false, 0.006);
  // The notch (hull in two forward of it) and the dome's nose (aft of it the dome and the stem
  // are in two as well); not the deck's forward end, the run's least x.
  ASSERT_EQ(turns.size(), 2u);
  EXPECT_DOUBLE_EQ(turns[0].x, -2.665);
  EXPECT_EQ(turns[0].side, +1);
  EXPECT_DOUBLE_EQ(turns[1].x, -2.631);
  EXPECT_EQ(turns[1].side, -1);
  EXPECT_DOUBLE_EQ(turns[1].clear, 0.1);
  // Both branches must reach: from the notch, the dome's front runs 34 mm forward before the
  // keel turns it back; from the nose, the dome runs 34 mm aft before the stem turns it back.
  EXPECT_EQ(profile_turns(dtmb_profile(), false, 0.03).size(), 2u);
  EXPECT_TRUE(profile_turns(dtmb_profile(), false, 0.04).empty());
  // A notch standing at one x counts once; the nose below it, at the run's least x, not at all.
  const std::vector<BoundaryTurn> flat = profile_turns(std::vector<Vec3d>{{-3, 0, 1},
                                                                          {-2, 0, 0.5},
                                                                          {-1, 0, 0.2},
                                                                          {-1, 0, 0},
                                                                          {-1, 0, -0.2},
                                                                          {-2, 0, -0.5},
                                                                          {-3, 0, -1},
                                                                          {-2, 0, -1.1},
                                                                          {1, 0, -1.1}},
                                                       false, 0.1);
  ASSERT_EQ(flat.size(), 1u);
  EXPECT_DOUBLE_EQ(flat[0].x, -1);
  EXPECT_EQ(flat[0].side, -1);
  // A wiggle smaller than the reach, and a straight keel: nothing.
  EXPECT_TRUE(profile_turns(
                  std::vector<Vec3d>{{0, 0, 0}, {1, 0, 0}, {0.999, 0, 0.01}, {2, 0, 0}, {3, 0, 0}},
                  false, 0.1)
                  .empty());
}

TEST(PlanStations, CentrePlaneTurnsComeFromCentrePlaneRunsOnly) {
  const RunCase profile = run_through(dtmb_profile(), BoundaryKind::kCentrePlane);
  EXPECT_EQ(centre_plane_turns(profile.surface, profile.features, 0.03).size(), 2u);
  // hx 0.03: the reach is 0.006 m, as above. A deck edge or a waterline of that shape: none.
  const RunCase deck = run_through(dtmb_profile(), BoundaryKind::kDeckEdge);
  EXPECT_TRUE(centre_plane_turns(deck.surface, deck.features, 0.03).empty());
  const RunCase water = run_through(dtmb_profile(), BoundaryKind::kWaterline);
  EXPECT_TRUE(centre_plane_turns(water.surface, water.features, 0.03).empty());
}

}  // namespace
}  // namespace hm::structured
