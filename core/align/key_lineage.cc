#include "core/align/key_lineage.h"

#include <algorithm>
#include <cstddef>
#include <deque>
#include <vector>

namespace alignset {
namespace {

bool IsRoot(const CanonicalDirections& key) {
  if (key.count == 1) return key.phi1 == 7 || key.phi1 == 22 || key.phi1 == 37;
  return key.phi1 % 10 == 0 && key.phi2 % 10 == 0;
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

// Breadth-first from the roots over the graph whose edges are single-degree
// steps (through Canonicalize, so the torus of directions and the orbits are
// handled once, there); each key's parent is its first neighbour, in
// NeighbourRequests order, one step closer to a root.
std::vector<Node> BuildLineage(int count) {
  const size_t size = CanonicalKeyCount(count);
  std::vector<Node> nodes(size);
  std::vector<std::vector<size_t>> neighbours(size);
  std::vector<std::vector<Canonicalization>> via(size);
  std::deque<size_t> queue;
  for (size_t i = 0; i < size; ++i) {
    const CanonicalDirections key = CanonicalKeyAt(count, i);
    for (const auto& request : NeighbourRequests(key)) {
      auto c = Canonicalize(request);
      if (!c.ok()) continue;  // cannot happen for finite whole degrees
      neighbours[i].push_back(*CanonicalKeyIndex(c->key));
      via[i].push_back(*c);
    }
    if (IsRoot(key)) {
      nodes[i].depth = 0;
      queue.push_back(i);
    }
  }
  while (!queue.empty()) {
    const size_t i = queue.front();
    queue.pop_front();
    for (size_t j : neighbours[i]) {
      if (nodes[j].depth >= 0) continue;
      nodes[j].depth = nodes[i].depth + 1;
      queue.push_back(j);
    }
  }
  for (size_t i = 0; i < size; ++i) {
    if (nodes[i].depth <= 0) continue;
    for (size_t k = 0; k < neighbours[i].size(); ++k) {
      if (nodes[neighbours[i][k]].depth == nodes[i].depth - 1) {
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
    // 30.25 -> 30, 30.5 -> 30.25, 30.75 -> 31: toward the nearest whole
    // degree, the lower one on the tie. Both are canonical as they stand.
    CanonicalDirections parent = key;
    if (key.phi1_quarter == 3) {
      parent = {1, key.phi1 + 1, key.phi1 + 1, 0};
    } else {
      parent.phi1_quarter -= 1;
    }
    return LineageParent{parent, AlignOps{}};
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
