// A dynamic AABB tree: a height-balanced binary tree of fattened boxes. Leaves are proxies
// (one per shape); inner nodes bound their children. Queries cost O(log n + hits), and a proxy
// whose shape stays inside its fat box is never touched, so resting bodies cost nothing.
#pragma once

#include <impulse2d/math.hpp>

#include <cstdint>
#include <vector>

namespace impulse2d {

class DynamicTree {
 public:
  static constexpr int kNull = -1;

  int createProxy(const Aabb& fatAabb, int64_t userData);
  void destroyProxy(int proxy);
  /// Re-inserts the proxy with a new fat box.
  void moveProxy(int proxy, const Aabb& fatAabb);

  const Aabb& fatAabb(int proxy) const { return nodes_[proxy].aabb; }
  int64_t userData(int proxy) const { return nodes_[proxy].userData; }
  int height() const { return root_ == kNull ? 0 : nodes_[root_].height; }

  /// Calls visit(proxy) for every leaf whose fat box overlaps `box`.
  template <class Visit>
  void query(const Aabb& box, Visit&& visit) const {
    if (root_ == kNull) return;
    stack_.clear();
    stack_.push_back(root_);
    while (!stack_.empty()) {
      const int id = stack_.back();
      stack_.pop_back();
      const Node& node = nodes_[id];
      if (!node.aabb.overlaps(box)) continue;
      if (node.isLeaf()) {
        visit(id);
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
  mutable std::vector<int> stack_;
};

}  // namespace impulse2d
