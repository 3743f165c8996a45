#include "dynamic_tree.hpp"

#include <algorithm>

namespace impulse2d {

int DynamicTree::allocateNode() {
  if (freeList_ == kNull) {
    nodes_.emplace_back();
    return static_cast<int>(nodes_.size()) - 1;
  }
  const int id = freeList_;
  freeList_ = nodes_[id].parent;
  nodes_[id] = Node();
  return id;
}

void DynamicTree::freeNode(int id) {
  nodes_[id].parent = freeList_;
  nodes_[id].height = -1;
  freeList_ = id;
}

int DynamicTree::createProxy(const Aabb& fatAabb, int64_t userData) {
  const int leaf = allocateNode();
  nodes_[leaf].aabb = fatAabb;
  nodes_[leaf].userData = userData;
  nodes_[leaf].height = 0;
  insertLeaf(leaf);
  ++proxyCount_;
  return leaf;
}

void DynamicTree::destroyProxy(int proxy) {
  removeLeaf(proxy);
  freeNode(proxy);
  --proxyCount_;
}

void DynamicTree::rebuild(const ForEachTask& forEach) {
  if (root_ == kNull) return;
  // Every node that is not a leaf goes back to the free list, lowest id first out.
  leaves_.clear();
  freeList_ = kNull;
  for (int id = static_cast<int>(nodes_.size()) - 1; id >= 0; --id) {
    Node& node = nodes_[id];
    if (node.height == 0) {
      const Vec2 c = 0.5 * (node.aabb.lower + node.aabb.upper);
      leaves_.push_back(LeafCenter{c.x(), c.y(), id});
    } else {
      freeNode(id);
    }
  }
  // The inner nodes' ids, taken from the free list in the order a build one node after the
  // other takes them (preorder), so that branches built side by side give the same tree.
  innerIds_.resize(leaves_.size() - 1);
  for (int& id : innerIds_) id = allocateNode();
  const Branch all{leaves_.data(), leaves_.data() + leaves_.size(), innerIds_.data()};
  constexpr size_t kLeavesPerTask = 256;  // smaller branches are not worth a task
  if (!forEach || leaves_.size() < 4 * kLeavesPerTask) {
    root_ = buildBranch(all);
  } else {
    // The top splits here, then the branches under them as tasks (about 16, a few per thread
    // of any count that pays), then the top nodes joined bottom up.
    tasks_.clear();
    topNodes_.clear();
    int depth = 0;
    while (depth < 4 && (leaves_.size() >> (depth + 1)) >= kLeavesPerTask) ++depth;
    root_ = splitTop(all, depth);
    forEach(static_cast<int>(tasks_.size()), [this](int k) { buildBranch(tasks_[k]); });
    for (auto top = topNodes_.rbegin(); top != topNodes_.rend(); ++top) {
      link((*top)[0], (*top)[1], (*top)[2]);
    }
  }
  nodes_[root_].parent = kNull;
}

// Splits the leaves in two halves along the longer side of their centres' box; returns the
// first leaf of the second half.
DynamicTree::LeafCenter* DynamicTree::split(const Branch& branch) {
  LeafCenter* const first = branch.first;
  LeafCenter* const last = branch.last;
  double minX = first->x, maxX = first->x, minY = first->y, maxY = first->y;
  for (const LeafCenter* leaf = first + 1; leaf != last; ++leaf) {
    minX = std::min(minX, leaf->x);
    maxX = std::max(maxX, leaf->x);
    minY = std::min(minY, leaf->y);
    maxY = std::max(maxY, leaf->y);
  }
  LeafCenter* middle = first + (last - first) / 2;
  if (maxX - minX >= maxY - minY) {
    std::nth_element(first, middle, last, [](const LeafCenter& a, const LeafCenter& b) {
      return a.x < b.x || (a.x == b.x && a.id < b.id);
    });
  } else {
    std::nth_element(first, middle, last, [](const LeafCenter& a, const LeafCenter& b) {
      return a.y < b.y || (a.y == b.y && a.id < b.id);
    });
  }
  return middle;
}

// The branch's node over its two halves, each built the same way.
int DynamicTree::buildBranch(const Branch& branch) {
  if (branch.last - branch.first == 1) return branch.first->id;
  LeafCenter* middle = split(branch);
  const int node = branch.ids[0];
  const int child1 = buildBranch({branch.first, middle, branch.ids + 1});
  const int child2 = buildBranch({middle, branch.last, branch.ids + (middle - branch.first)});
  link(node, child1, child2);
  return node;
}

// buildBranch's top `depth` levels: the branches below them are left in tasks_, and the nodes
// above them in topNodes_ to be linked once those are built. Returns the branch's node.
int DynamicTree::splitTop(const Branch& branch, int depth) {
  if (branch.last - branch.first == 1) return branch.first->id;
  if (depth == 0) {
    tasks_.push_back(branch);
    return branch.ids[0];
  }
  LeafCenter* middle = split(branch);
  const int node = branch.ids[0];
  const size_t top = topNodes_.size();
  topNodes_.push_back({node, kNull, kNull});
  topNodes_[top][1] = splitTop({branch.first, middle, branch.ids + 1}, depth - 1);
  topNodes_[top][2] =
      splitTop({middle, branch.last, branch.ids + (middle - branch.first)}, depth - 1);
  return node;
}

void DynamicTree::link(int node, int child1, int child2) {
  Node& n = nodes_[node];
  n.child1 = child1;
  n.child2 = child2;
  n.aabb = nodes_[child1].aabb.united(nodes_[child2].aabb);
  n.height = 1 + std::max(nodes_[child1].height, nodes_[child2].height);
  nodes_[child1].parent = node;
  nodes_[child2].parent = node;
}

void DynamicTree::moveProxy(int proxy, const Aabb& fatAabb) {
  removeLeaf(proxy);
  nodes_[proxy].aabb = fatAabb;
  insertLeaf(proxy);
}

// Descends towards the sibling that makes the tree's total perimeter grow least: at each node,
// either pair the new leaf with the node itself, or pay the node's growth and go deeper.
int DynamicTree::chooseSibling(const Aabb& box) const {
  int index = root_;
  while (!nodes_[index].isLeaf()) {
    const Node& node = nodes_[index];
    const double perimeter = node.aabb.perimeter();
    const double combined = node.aabb.united(box).perimeter();
    const double costHere = 2.0 * combined;
    const double inherited = 2.0 * (combined - perimeter);
    auto descendCost = [&](int child) {
      const Aabb grown = nodes_[child].aabb.united(box);
      const double growth = nodes_[child].isLeaf()
                                ? grown.perimeter()
                                : grown.perimeter() - nodes_[child].aabb.perimeter();
      return growth + inherited;
    };
    const double cost1 = descendCost(node.child1);
    const double cost2 = descendCost(node.child2);
    if (costHere < cost1 && costHere < cost2) break;
    index = cost1 < cost2 ? node.child1 : node.child2;
  }
  return index;
}

void DynamicTree::insertLeaf(int leaf) {
  if (root_ == kNull) {
    root_ = leaf;
    nodes_[leaf].parent = kNull;
    return;
  }
  const Aabb box = nodes_[leaf].aabb;
  const int sibling = chooseSibling(box);

  //   oldParent            oldParent
  //       |         ->         |
  //    sibling              newParent
  //                          /     \.
  //                     sibling    leaf
  const int oldParent = nodes_[sibling].parent;
  const int newParent = allocateNode();
  nodes_[newParent].parent = oldParent;
  nodes_[newParent].aabb = box.united(nodes_[sibling].aabb);
  nodes_[newParent].height = nodes_[sibling].height + 1;
  nodes_[newParent].child1 = sibling;
  nodes_[newParent].child2 = leaf;
  nodes_[sibling].parent = newParent;
  nodes_[leaf].parent = newParent;
  if (oldParent == kNull) {
    root_ = newParent;
  } else if (nodes_[oldParent].child1 == sibling) {
    nodes_[oldParent].child1 = newParent;
  } else {
    nodes_[oldParent].child2 = newParent;
  }
  refit(nodes_[leaf].parent);
}

void DynamicTree::removeLeaf(int leaf) {
  if (leaf == root_) {
    root_ = kNull;
    return;
  }
  // The parent goes away and the sibling takes its place.
  const int parent = nodes_[leaf].parent;
  const int grandParent = nodes_[parent].parent;
  const int sibling = nodes_[parent].child1 == leaf ? nodes_[parent].child2 : nodes_[parent].child1;
  if (grandParent == kNull) {
    root_ = sibling;
    nodes_[sibling].parent = kNull;
    freeNode(parent);
    return;
  }
  if (nodes_[grandParent].child1 == parent) {
    nodes_[grandParent].child1 = sibling;
  } else {
    nodes_[grandParent].child2 = sibling;
  }
  nodes_[sibling].parent = grandParent;
  freeNode(parent);
  refit(grandParent);
}

// Walks to the root, rebalancing and recomputing heights and boxes on the way.
void DynamicTree::refit(int from) {
  int index = from;
  while (index != kNull) {
    index = balance(index);
    Node& node = nodes_[index];
    node.height = 1 + std::max(nodes_[node.child1].height, nodes_[node.child2].height);
    node.aabb = nodes_[node.child1].aabb.united(nodes_[node.child2].aabb);
    index = node.parent;
  }
}

// An AVL rotation at node A when one child is more than one level taller than the other. Shown
// for the right child C being taller (the left case mirrors it):
//
//        A                 C
//       / \               / \.
//      B   C     ->      A   F      (F is the taller grandchild, it stays under C;
//         / \           / \          the shorter one, G, moves under A)
//        F   G         B   G
int DynamicTree::balance(int iA) {
  Node& a = nodes_[iA];
  if (a.isLeaf() || a.height < 2) return iA;

  const int iB = a.child1;
  const int iC = a.child2;
  const int tilt = nodes_[iC].height - nodes_[iB].height;
  if (tilt >= -1 && tilt <= 1) return iA;

  const bool rightTaller = tilt > 1;
  const int iUp = rightTaller ? iC : iB;  // the child that becomes A's parent
  const int iStay = rightTaller ? iB : iC;
  Node& up = nodes_[iUp];
  const int iX = up.child1;
  const int iY = up.child2;
  const int iTall = nodes_[iX].height > nodes_[iY].height ? iX : iY;
  const int iShort = iTall == iX ? iY : iX;

  up.child1 = iA;
  up.parent = a.parent;
  a.parent = iUp;
  if (up.parent == kNull) {
    root_ = iUp;
  } else if (nodes_[up.parent].child1 == iA) {
    nodes_[up.parent].child1 = iUp;
  } else {
    nodes_[up.parent].child2 = iUp;
  }

  up.child2 = iTall;
  if (rightTaller) {
    a.child2 = iShort;
  } else {
    a.child1 = iShort;
  }
  nodes_[iShort].parent = iA;
  a.aabb = nodes_[iStay].aabb.united(nodes_[iShort].aabb);
  a.height = 1 + std::max(nodes_[iStay].height, nodes_[iShort].height);
  up.aabb = a.aabb.united(nodes_[iTall].aabb);
  up.height = 1 + std::max(a.height, nodes_[iTall].height);
  return iUp;
}

}  // namespace impulse2d
