#include "core/align/key_lineage.h"

#include <algorithm>
#include <cstddef>
#include <deque>
#include <limits>
#include <vector>

namespace alignset {
namespace {

// Chains are at most this long: every warm step leaves the set a little
// worse on the integrands nobody aligned it to (the triangle lost 1.5%
// after one step, 4% after three, 7% after five and 12% after ten; N =
// 4096, 12 seeds), so no key is more than three steps from its root.
constexpr int kMaxDepth = 3;

// The regular part of the roots. One direction: every 7th degree, so no
// key is more than 3 away. Two directions: the lattice 3 phi1 + 4 phi2 = 0
// (mod 25), whose diamonds of radius 3 tile the plane; where the canonical
// space's edges cut them, BuildLineage adds roots.
bool IsLatticeRoot(const CanonicalDirections& key) {
  if (key.count == 1) return key.phi1 % 7 == 1;
  return (3 * key.phi1 + 4 * key.phi2) % 25 == 0;
}

// The requests one whole degree from the key, in the fixed order that
// breaks ties between equally deep parents.
std::vector<std::vector<double>> NeighbourRequests(const CanonicalDirections& key) {
  const double a = key.phi1, b = key.phi2;
  if (key.count == 1) return {{a - 1}, {a + 1}};
  return {{a - 1, b}, {a + 1, b}, {a, b - 1}, {a, b + 1}};
}

struct Node {
  int depth = -1;
  std::optional<LineageParent> parent;
};

// The graph whose edges are single-degree steps (through Canonicalize, so
// the torus of directions and the orbits are handled once, there). Roots:
// the lattice roots, then, in key order, every key still more than
// kMaxDepth steps from a root. A key's depth is its distance to the nearest
// root, and its parent its first neighbour, in NeighbourRequests order, one
// step closer.
std::vector<Node> BuildLineage(int count) {
  const size_t size = CanonicalKeyCount(count);
  std::vector<Node> nodes(size);
  std::vector<std::vector<size_t>> neighbours(size);
  std::vector<std::vector<Canonicalization>> via(size);
  for (size_t i = 0; i < size; ++i) {
    const CanonicalDirections key = CanonicalKeyAt(count, i);
    for (const auto& request : NeighbourRequests(key)) {
      auto c = Canonicalize(request);
      if (!c.ok()) continue;  // cannot happen for finite whole degrees
      neighbours[i].push_back(*CanonicalKeyIndex(c->key));
      via[i].push_back(*c);
    }
  }
  std::vector<int> distance(size, std::numeric_limits<int>::max());
  auto add_root = [&](size_t root) {
    distance[root] = 0;
    std::deque<size_t> queue = {root};
    while (!queue.empty()) {
      const size_t i = queue.front();
      queue.pop_front();
      for (size_t j : neighbours[i]) {
        if (distance[j] <= distance[i] + 1) continue;
        distance[j] = distance[i] + 1;
        queue.push_back(j);
      }
    }
  };
  for (size_t i = 0; i < size; ++i) {
    if (IsLatticeRoot(CanonicalKeyAt(count, i))) add_root(i);
  }
  for (size_t i = 0; i < size; ++i) {
    if (distance[i] > kMaxDepth) add_root(i);
  }
  for (size_t i = 0; i < size; ++i) {
    nodes[i].depth = distance[i];
    if (distance[i] == 0) continue;
    for (size_t k = 0; k < neighbours[i].size(); ++k) {
      if (distance[neighbours[i][k]] == distance[i] - 1) {
        nodes[i].parent = LineageParent{via[i][k].key, via[i][k].ops};
        break;
      }
    }
  }
  return nodes;
}

const std::vector<Node>& Lineage(int count) {
  static const std::vector<Node> single = BuildLineage(1);
  static const std::vector<Node> pairs = BuildLineage(2);
  return count == 1 ? single : pairs;
}

// The whole-degree node of a key, or null when the key is not canonical.
const Node* WholeDegreeNode(const CanonicalDirections& key) {
  if (key.count != 1 && key.count != 2) return nullptr;
  auto index = CanonicalKeyIndex(key);
  if (!index.ok()) return nullptr;
  return &Lineage(key.count)[*index];
}

bool IsQuarterKey(const CanonicalDirections& key) {
  return key.count == 1 && key.phi1_quarter != 0 && CanonicalKeyIndex(key, AngleGrid::kQuarterDegree).ok();
}

}  // namespace

std::optional<LineageParent> WarmParent(const CanonicalDirections& key) {
  if (IsQuarterKey(key)) {
    // 30.25 -> 30, 30.5 -> 30, 30.75 -> 31: the nearest whole degree, the
    // lower one on the tie, in one step. Both are canonical as they stand.
    const int whole = key.phi1 + (key.phi1_quarter == 3 ? 1 : 0);
    return LineageParent{{1, whole, whole, 0}, AlignOps{}};
  }
  const Node* node = WholeDegreeNode(key);
  if (node == nullptr) return std::nullopt;
  return node->parent;
}

int LineageDepth(const CanonicalDirections& key) {
  if (IsQuarterKey(key)) return 1 + LineageDepth(WarmParent(key)->parent);
  const Node* node = WholeDegreeNode(key);
  return node == nullptr ? -1 : node->depth;
}

CanonicalDirections LineageRoot(const CanonicalDirections& key) {
  CanonicalDirections root = key;
  while (auto parent = WarmParent(root)) root = parent->parent;
  return root;
}

int MaxLineageDepth(int count, AngleGrid grid) {
  int depth = -1;
  const size_t size = CanonicalKeyCount(count, grid);
  for (size_t i = 0; i < size; ++i) depth = std::max(depth, LineageDepth(CanonicalKeyAt(count, i, grid)));
  return depth;
}

}  // namespace alignset
