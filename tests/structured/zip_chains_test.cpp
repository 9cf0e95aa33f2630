// Zipping two node chains: equal chains give quads only, a longer chain adds one triangle per
// extra node, shared ends give triangles, every face turns the same way, and a twisted quad is
// split.
#include <gtest/gtest.h>

#include <map>
#include <utility>
#include <vector>

#include "structured/structured_steps.h"

namespace hm::structured {
namespace {

// Chain a along y at x = 0, chain b along y at x = 1 (n + 1 and m + 1 evenly spaced nodes).
struct Chains {
  std::vector<Vec3d> pos;
  std::vector<Index> a, b;
  std::vector<double> fa, fb;
};

Chains make(int n, int m) {
  Chains c;
  for (int i = 0; i <= n; ++i) {
    c.a.push_back(static_cast<Index>(c.pos.size()));
    c.fa.push_back(double(i) / n);
    c.pos.push_back({0, double(i) / n, 0});
  }
  for (int k = 0; k <= m; ++k) {
    c.b.push_back(static_cast<Index>(c.pos.size()));
    c.fb.push_back(double(k) / m);
    c.pos.push_back({1, double(k) / m, 0});
  }
  return c;
}

// Every interior edge is used once in each direction, and every face's normal has the same sign
// of z.
void expect_consistent(const std::vector<Face>& faces, const std::vector<Vec3d>& pos) {
  std::map<std::pair<Index, Index>, int> directed;
  double sign = 0;
  for (const Face& f : faces) {
    const int n = corner_count(f);
    for (int c = 0; c < n; ++c) ++directed[{f[c], f[(c + 1) % n]}];
    const double z = face_normal(pos, f).z;
    EXPECT_NE(z, 0);
    if (sign == 0) sign = z;
    EXPECT_GT(z * sign, 0);
  }
  for (const auto& [e, uses] : directed) EXPECT_EQ(uses, 1) << e.first << "-" << e.second;
}

TEST(ZipChains, EqualChainsGiveQuadsOnly) {
  Chains c = make(6, 6);
  std::vector<Face> faces;
  const ZipCounts n = zip_chains(c.a, c.fa, c.b, c.fb, c.pos, {}, faces);
  EXPECT_EQ(n.quads, 6u);
  EXPECT_EQ(n.triangles, 0u);
  expect_consistent(faces, c.pos);
}

TEST(ZipChains, EachExtraNodeAddsOneTriangle) {
  for (int extra : {1, 2, 3}) {
    Chains c = make(6, 6 + extra);
    std::vector<Face> faces;
    const ZipCounts n = zip_chains(c.a, c.fa, c.b, c.fb, c.pos, {}, faces);
    EXPECT_EQ(n.quads, 6u);
    EXPECT_EQ(n.triangles, static_cast<std::size_t>(extra));
    expect_consistent(faces, c.pos);
  }
}

TEST(ZipChains, SharedEndsBecomeTriangles) {
  // A cap: chain b starts and ends at a's end nodes.
  Chains c = make(4, 4);
  c.b.front() = c.a.front();
  c.b.back() = c.a.back();
  std::vector<Face> faces;
  const ZipCounts n = zip_chains(c.a, c.fa, c.b, c.fb, c.pos, {}, faces);
  EXPECT_EQ(n.quads, 2u);
  EXPECT_EQ(n.triangles, 2u);
  for (const Face& f : faces) {
    const int m = corner_count(f);
    for (int i = 0; i < m; ++i)
      for (int j = i + 1; j < m; ++j) EXPECT_NE(f[i], f[j]);
  }
}

// A cap whose boundary path has one node of its own (a dome's nose just beyond the row): no
// face may have all its corners on the row, where the end nodes fanned over the row's own
// edges, three nodes in a row, before.
TEST(ZipChains, ASharedEndDoesNotFanOverItsOwnChain) {
  for (int n : {4, 6, 10}) {
    Chains c = make(n, 2);
    c.b.front() = c.a.front();
    c.b.back() = c.a.back();
    std::vector<Face> faces;
    zip_chains(c.a, c.fa, c.b, c.fb, c.pos, {}, faces);
    expect_consistent(faces, c.pos);
    const Index tip = c.b[1];
    for (const Face& f : faces) {
      bool off_a = false;
      for (int k = 0; k < corner_count(f); ++k) off_a = off_a || f[k] == tip;
      EXPECT_TRUE(off_a) << n << ": " << f[0] << " " << f[1] << " " << f[2];
    }
  }
}

TEST(ZipChains, TwistedQuadIsSplit) {
  Chains c = make(1, 1);
  c.pos[c.b[1]].z = 1.5;  // lifts one corner far off the plane of the other three
  std::vector<Face> faces;
  const ZipCounts n = zip_chains(c.a, c.fa, c.b, c.fb, c.pos, {}, faces);
  EXPECT_EQ(n.split, 1u);
  EXPECT_EQ(n.quads, 0u);
  EXPECT_EQ(n.triangles, 2u);
  // Flat again: the same quad stays whole.
  c.pos[c.b[1]].z = 0;
  faces.clear();
  EXPECT_EQ(zip_chains(c.a, c.fa, c.b, c.fb, c.pos, {}, faces).quads, 1u);
}

}  // namespace
}  // namespace hm::structured
