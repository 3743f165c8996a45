// A dynamic AABB tree: a height-balanced binary tree of fattened boxes. Leaves are proxies
// (one per shape); inner nodes bound their children. Queries cost O(log n + hits), and a proxy
// whose shape stays inside its fat box is never touched, so resting bodies cost nothing.
#pragma once

#include <impulse2d/math.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

namespace impulse2d {

class DynamicTree {
 public:
  static constexpr int kNull = -1;

  int createProxy(const Aabb& fatAabb, int64_t userData);
  void destroyProxy(int proxy);
  /// Re-inserts the proxy with a new fat box.
  void moveProxy(int proxy, const Aabb& fatAabb);
  /// Gives the proxy a new fat box without touching the tree above it: rebuild() must follow
  /// before the next query (for many proxies moved at once).
  void setFatAabb(int proxy, const Aabb& fatAabb) { nodes_[proxy].aabb = fatAabb; }
  /// Runs task(i) for every i in [0, count), on several threads if it likes, and returns when
  /// all are done.
  using ForEachTask = std::function<void(int count, const std::function<void(int)>& task)>;
  /// Builds every inner node anew over the leaves, top down; the proxies keep their ids and
  /// boxes, so every query meets the same proxies (in another order). With `forEach`, the
  /// branches below the top few splits are built as tasks: the same tree, node for node.
  void rebuild(const ForEachTask& forEach = nullptr);
  int proxyCount() const { return proxyCount_; }

  const Aabb& fatAabb(int proxy) const { return nodes_[proxy].aabb; }
  int64_t userData(int proxy) const { return nodes_[proxy].userData; }
  int height() const { return root_ == kNull ? 0 : nodes_[root_].height; }

  /// Calls visit(proxy) for every leaf whose fat box overlaps `box`.
  template <class Visit>
  void query(const Aabb& box, Visit&& visit) const {
    query(box, stack_, visit);
  }

  /// The same on the caller's stack, so that threads may query at once.
  template <class Visit>
  void query(const Aabb& box, std::vector<int>& stack, Visit&& visit) const {
    if (root_ == kNull || !nodes_[root_].aabb.overlaps(box)) return;
    if (nodes_[root_].isLeaf()) {
      visit(root_);
      return;
    }
    // The stack holds inner nodes known to overlap: each child is tested where its parent is
    // read, so a node that misses is never pushed.
    stack.clear();
    stack.push_back(root_);
    while (!stack.empty()) {
      const Node& node = nodes_[stack.back()];
      stack.pop_back();
      for (const int child : {node.child1, node.child2}) {
        const Node& c = nodes_[child];
        if (!c.aabb.overlaps(box)) continue;
        if (c.isLeaf()) {
          visit(child);
        } else {
          stack.push_back(child);
        }
      }
    }
  }

  /// Walks the leaves whose fat box the segment p1 -> p2 may cross, up to `maxFraction` of it.
  /// visit(proxy, maxFraction) returns the fraction to clip the segment to from then on: its
  /// hit's, to look only for nearer ones; maxFraction, to go on as before; 0 to stop.
  /// A node is skipped when the segment's box misses it, or when the node lies wholly on one side
  /// of the segment's line (the separating axis v = perp(p2 - p1)):
  ///
  ///        +-----+          |v . (p1 - c)| > |v| . h : every corner of the box (centre c,
  ///        |  c  |                                     half extents h) is on one side
  ///        +-----+
  ///   p1 ---------------> p2
  ///
  /// visit(proxy, maxFraction) returns the fraction to clip the segment to, or a negative
  /// number to end the cast. A hit at fraction 0 (a ray that starts inside a shape) does not end
  /// it: other shapes may contain the start too, and the caller chooses among equals.
  template <class Visit>
  void rayCast(const Vec2& p1, const Vec2& p2, double maxFraction, Visit&& visit) const {
    if (root_ == kNull) return;
    const Vec2 d = p2 - p1;
    const Vec2 v = perp(d);
    const Vec2 absV = v.cwiseAbs();
    auto segmentBox = [&](double fraction) {
      const Vec2 end = p1 + fraction * d;
      return Aabb{p1.cwiseMin(end), p1.cwiseMax(end)};
    };
    Aabb box = segmentBox(maxFraction);
    stack_.clear();
    stack_.push_back(root_);
    while (!stack_.empty()) {
      const int id = stack_.back();
      stack_.pop_back();
      const Node& node = nodes_[id];
      if (!node.aabb.overlaps(box)) continue;
      const Vec2 c = 0.5 * (node.aabb.lower + node.aabb.upper);
      const Vec2 h = 0.5 * (node.aabb.upper - node.aabb.lower);
      if (std::abs(v.dot(p1 - c)) - absV.dot(h) > 0.0) continue;
      if (node.isLeaf()) {
        const double clipped = visit(id, maxFraction);
        if (clipped < 0.0) return;
        if (clipped < maxFraction) {
          maxFraction = clipped;
          box = segmentBox(maxFraction);
        }
      } else {
        stack_.push_back(node.child1);
        stack_.push_back(node.child2);
      }
    }
  }

 private:
  struct Node {
    Aabb aabb;
    int64_t userData = 0;
    int parent = kNull;  // doubles as the free-list link for unused nodes
    int child1 = kNull;
    int child2 = kNull;
    int height = 0;  // leaf = 0, free = -1
    bool isLeaf() const { return child1 == kNull; }
  };

  // A leaf and its box's centre, as rebuild() sorts them.
  struct LeafCenter {
    double x, y;
    int id;
  };
  // A branch over leaves [first, last) whose inner nodes take the ids ids[0, last - first - 1)
  // in preorder: the node itself ids[0], then its first child's branch, then the second's.
  struct Branch {
    LeafCenter* first;
    LeafCenter* last;
    const int* ids;
  };
  static LeafCenter* split(const Branch& branch);
  int buildBranch(const Branch& branch);
  int splitTop(const Branch& branch, int depth);
  void link(int node, int child1, int child2);
  int allocateNode();
  void freeNode(int id);
  void insertLeaf(int leaf);
  void removeLeaf(int leaf);
  int chooseSibling(const Aabb& box) const;
  int balance(int a);
  void refit(int from);

  std::vector<Node> nodes_;
  int root_ = kNull;
  int freeList_ = kNull;
  int proxyCount_ = 0;
  mutable std::vector<int> stack_;
  // rebuild()'s: the leaves, the inner nodes' ids, the branches left to tasks, and the top
  // nodes (node, child1, child2) in preorder.
  std::vector<LeafCenter> leaves_;
  std::vector<int> innerIds_;
  std::vector<Branch> tasks_;
  std::vector<std::array<int, 3>> topNodes_;
};

}  // namespace impulse2d
