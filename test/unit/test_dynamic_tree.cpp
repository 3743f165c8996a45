// The broad phase's tree must report exactly the overlaps a brute-force scan reports, stay
// balanced, and reuse its nodes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>

#include "dynamic_tree.hpp"

namespace impulse2d {
namespace {

Aabb randomBox(std::mt19937& rng) {
  std::uniform_real_distribution<double> pos(-50.0, 50.0), size(0.1, 3.0);
  const Vec2 lower(pos(rng), pos(rng));
  return Aabb{lower, lower + Vec2(size(rng), size(rng))};
}

std::set<int> treeHits(const DynamicTree& tree, const Aabb& box) {
  std::set<int> hits;
  tree.query(box, [&](int proxy) { hits.insert(proxy); });
  return hits;
}

TEST(DynamicTree, QueriesMatchBruteForceThroughInsertsMovesAndRemovals) {
  std::mt19937 rng(42);
  DynamicTree tree;
  std::vector<int> proxies;
  std::vector<Aabb> boxes;
  for (int i = 0; i < 1000; ++i) {
    boxes.push_back(randomBox(rng));
    proxies.push_back(tree.createProxy(boxes.back(), i));
  }
  for (int round = 0; round < 3; ++round) {
    for (int q = 0; q < 200; ++q) {
      const Aabb query = randomBox(rng);
      std::set<int> expected;
      for (size_t i = 0; i < proxies.size(); ++i) {
        if (boxes[i].overlaps(query)) expected.insert(proxies[i]);
      }
      ASSERT_EQ(treeHits(tree, query), expected);
    }
    // Move a third, remove a tenth.
    for (size_t i = 0; i < proxies.size(); i += 3) {
      boxes[i] = randomBox(rng);
      tree.moveProxy(proxies[i], boxes[i]);
    }
    for (size_t i = proxies.size(); i-- > 0;) {
      if (i % 10 == static_cast<size_t>(round)) {
        tree.destroyProxy(proxies[i]);
        proxies.erase(proxies.begin() + i);
        boxes.erase(boxes.begin() + i);
      }
    }
  }
  // A balanced binary tree of n leaves is about log2(n) deep; AVL bounds it by 1.44 log2(n).
  EXPECT_LE(tree.height(), 1.44 * std::log2(static_cast<double>(proxies.size())) + 2);
}

// Many proxies given new boxes in place and the tree rebuilt, then moved, removed and added one
// by one again: every query still meets exactly what a scan meets, the rebuilt tree is as shallow
// as halving gives, and it uses no more nodes than it had.
TEST(DynamicTree, RebuiltTreeQueriesMatchBruteForceAndTakesIncrementalEditsAfter) {
  std::mt19937 rng(7);
  DynamicTree tree;
  std::vector<int> proxies;
  std::vector<Aabb> boxes;
  for (int i = 0; i < 1000; ++i) {
    boxes.push_back(randomBox(rng));
    proxies.push_back(tree.createProxy(boxes.back(), i));
  }
  const int highest = *std::max_element(proxies.begin(), proxies.end());
  auto expectMatches = [&] {
    for (int q = 0; q < 200; ++q) {
      const Aabb query = randomBox(rng);
      std::set<int> expected;
      for (size_t i = 0; i < proxies.size(); ++i) {
        if (boxes[i].overlaps(query)) expected.insert(proxies[i]);
      }
      ASSERT_EQ(treeHits(tree, query), expected);
    }
  };
  for (int round = 0; round < 3; ++round) {
    for (size_t i = round; i < proxies.size(); i += 2) {  // half of them, in place
      boxes[i] = randomBox(rng);
      tree.setFatAabb(proxies[i], boxes[i]);
    }
    tree.rebuild();
    EXPECT_EQ(tree.proxyCount(), static_cast<int>(proxies.size()));
    EXPECT_EQ(tree.height(), static_cast<int>(std::ceil(std::log2(proxies.size()))));
    expectMatches();
    for (size_t i = 0; i < proxies.size(); i += 5) {
      boxes[i] = randomBox(rng);
      tree.moveProxy(proxies[i], boxes[i]);
    }
    tree.destroyProxy(proxies.back());
    proxies.pop_back();
    boxes.pop_back();
    expectMatches();
  }
  boxes.push_back(randomBox(rng));
  proxies.push_back(tree.createProxy(boxes.back(), -1));
  EXPECT_LE(proxies.back(), 2 * highest) << "the rebuild reused the inner nodes it freed";
  expectMatches();
}

TEST(DynamicTree, SortedInsertionStaysBalancedAndNodesAreReused) {
  DynamicTree tree;
  std::vector<int> proxies;
  for (int i = 0; i < 4096; ++i) {  // a row of boxes inserted in order: the worst case unbalanced
    proxies.push_back(tree.createProxy(Aabb{Vec2(i, 0.0), Vec2(i + 1.0, 1.0)}, i));
  }
  EXPECT_LE(tree.height(), 20);
  const int highest = *std::max_element(proxies.begin(), proxies.end());
  for (int proxy : proxies) tree.destroyProxy(proxy);
  for (int i = 0; i < 4096; ++i) {
    EXPECT_LE(tree.createProxy(Aabb{Vec2(0.0, i), Vec2(1.0, i + 1.0)}, i), 2 * highest);
  }
}

}  // namespace
}  // namespace impulse2d
