#include "iges/transforms.h"

#include <vector>

#include "core/error.h"

namespace hm::iges {
namespace {

// The matrix of one 124, without its own chain. Throws EntityFault when malformed.
Affine own_matrix(const IgesModel& m, int index) {
  const Params p(m, index);
  p.require(12, "a transformation matrix");
  Affine a;
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col)
      a.r[row][col] = p.real(static_cast<std::size_t>(4 * row + col + 1));
    a.t[row] = p.real(static_cast<std::size_t>(4 * row + 4));
  }
  a.identity = false;
  return a;
}

}  // namespace

Affine compose(const Affine& outer, const Affine& inner) {
  if (inner.identity) return outer;
  if (outer.identity) return inner;
  Affine c;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      c.r[i][j] = outer.r[i][0] * inner.r[0][j] + outer.r[i][1] * inner.r[1][j] +
                  outer.r[i][2] * inner.r[2][j];
    }
    c.t[i] = outer.r[i][0] * inner.t[0] + outer.r[i][1] * inner.t[1] + outer.r[i][2] * inner.t[2] +
             outer.t[i];
  }
  c.identity = false;
  return c;
}

Transforms::Transforms(const IgesModel& m) : m_(&m) {
  const int n = static_cast<int>(m.size());
  std::vector<int> path;
  for (int start = 0; start < n; ++start) {
    if (m.entries[static_cast<std::size_t>(start)].type != 124) continue;
    if (chain_.count(start) || bad_.count(start)) continue;
    // Walk to the end of the chain (or a resolved link), then fold back.
    path.clear();
    int cur = start;
    Affine tail;  // the resolved remainder beyond path.back()
    std::string tail_bad;
    while (true) {
      for (int seen : path) {
        if (seen == cur) {
          std::string chain;
          for (int k : path) chain += "DE " + std::to_string(2 * k + 1) + " -> ";
          chain += "DE " + std::to_string(2 * cur + 1);
          throw IgesError(m.source + ": DE " + std::to_string(2 * cur + 1) +
                          ": cyclic transformation chain (" + chain + ")");
        }
      }
      if (path.size() >= m.limits.max_pointer_depth) {
        throw IgesError(m.source + ": DE " + std::to_string(2 * start + 1) +
                        ": transformation chain deeper than " +
                        std::to_string(m.limits.max_pointer_depth) + " (limit max_pointer_depth)");
      }
      path.push_back(cur);
      const int next_de = m.entries[static_cast<std::size_t>(cur)].transform;
      if (next_de == 0) break;
      const int next = m.index_of(next_de);
      if (next < 0 || m.entries[static_cast<std::size_t>(next)].type != 124) {
        tail_bad =
            "its transformation pointer " + std::to_string(next_de) + " does not name a 124 entity";
        break;
      }
      if (auto it = chain_.find(next); it != chain_.end()) {
        tail = it->second;
        break;
      }
      if (auto it = bad_.find(next); it != bad_.end()) {
        tail_bad = it->second;
        break;
      }
      cur = next;
    }
    for (auto it = path.rbegin(); it != path.rend(); ++it) {
      if (!tail_bad.empty()) {
        bad_[*it] = tail_bad;
        continue;
      }
      try {
        tail = compose(tail, own_matrix(m, *it));
        chain_[*it] = tail;
      } catch (const EntityFault& f) {
        tail_bad = std::string("transformation matrix DE ") + std::to_string(2 * *it + 1) +
                   " is malformed: " + f.what();
        bad_[*it] = tail_bad;
      }
    }
  }
}

Affine Transforms::of(int index) const {
  const int de = m_->entries[static_cast<std::size_t>(index)].transform;
  if (de == 0) return Affine{};
  const int t = m_->index_of(de);
  if (t < 0) {
    throw EntityFault(index, "dangling transformation pointer: DE " + std::to_string(de) +
                                 " is not a directory entry of this file");
  }
  if (auto it = chain_.find(t); it != chain_.end()) return it->second;
  if (auto it = bad_.find(t); it != bad_.end()) throw EntityFault(index, it->second);
  throw EntityFault(index, "transformation pointer DE " + std::to_string(de) + " names a type " +
                               std::to_string(m_->entries[static_cast<std::size_t>(t)].type) +
                               " entity, not a 124");
}

}  // namespace hm::iges
