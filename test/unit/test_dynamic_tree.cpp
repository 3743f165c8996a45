// The broad phase's tree must report exactly the overlaps a brute-force scan reports, stay
// balanced, and reuse its nodes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>
#include <set>
#include <vector>

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

// A tree and, beside it, each proxy's box, for a brute-force scan to check the tree against.
struct CheckedTree {
  DynamicTree tree;
  std::vector<int> proxies;
  std::vector<Aabb> boxes;

  void addRandom(std::mt19937& rng, int count) {
    for (int i = 0; i < count; ++i) {
      boxes.push_back(randomBox(rng));
      proxies.push_back(tree.createProxy(boxes.back(), static_cast<int64_t>(proxies.size())));
    }
  }
  void expectQueriesMatchScan(std::mt19937& rng, int queries) const {
    for (int q = 0; q < queries; ++q) {
      const Aabb query = randomBox(rng);
      std::set<int> expected;
      for (size_t i = 0; i < proxies.size(); ++i) {
        if (boxes[i].overlaps(query)) expected.insert(proxies[i]);
      }
      ASSERT_EQ(treeHits(tree, query), expected);
    }
  }
  // Every stride-th proxy from `first` gets a new random box: moved in the tree, or only set in
  // place (`inPlace`: rebuild() must follow).
  void moveEvery(std::mt19937& rng, size_t first, size_t stride, bool inPlace) {
    for (size_t i = first; i < proxies.size(); i += stride) {
      boxes[i] = randomBox(rng);
      if (inPlace) {
        tree.setFatAabb(proxies[i], boxes[i]);
      } else {
        tree.moveProxy(proxies[i], boxes[i]);
      }
    }
  }
  void removeAt(size_t i) {
    tree.destroyProxy(proxies[i]);
    proxies.erase(proxies.begin() + static_cast<std::ptrdiff_t>(i));
    boxes.erase(boxes.begin() + static_cast<std::ptrdiff_t>(i));
  }
};

TEST(DynamicTree, QueriesMatchBruteForceThroughInsertsMovesAndRemovals) {
  std::mt19937 rng(42);
  CheckedTree checked;
  checked.addRandom(rng, 1000);
  for (int round = 0; round < 3; ++round) {
    checked.expectQueriesMatchScan(rng, 200);
    checked.moveEvery(rng, 0, 3, false);                 // a third moved
    for (size_t i = checked.proxies.size(); i-- > 0;) {  // a tenth removed
      if (i % 10 == static_cast<size_t>(round)) checked.removeAt(i);
    }
  }
  // A balanced binary tree of n leaves is about log2(n) deep; AVL bounds it by 1.44 log2(n).
  EXPECT_LE(checked.tree.height(),
            1.44 * std::log2(static_cast<double>(checked.proxies.size())) + 2);
}

// Many proxies given new boxes in place and the tree rebuilt, then moved, removed and added one
// by one again: every query still meets exactly what a scan meets, the rebuilt tree is as shallow
// as halving gives, and it uses no more nodes than it had.
TEST(DynamicTree, RebuiltTreeQueriesMatchBruteForceAndTakesIncrementalEditsAfter) {
  std::mt19937 rng(7);
  CheckedTree checked;
  checked.addRandom(rng, 1000);
  const std::vector<int>& proxies = checked.proxies;
  const int highest = *std::max_element(proxies.begin(), proxies.end());
  for (size_t round = 0; round < 3; ++round) {
    checked.moveEvery(rng, round, 2, true);  // half of them, in place
    checked.tree.rebuild();
    EXPECT_EQ(checked.tree.proxyCount(), static_cast<int>(proxies.size()));
    EXPECT_EQ(checked.tree.height(), static_cast<int>(std::ceil(std::log2(proxies.size()))));
    checked.expectQueriesMatchScan(rng, 200);
    checked.moveEvery(rng, 0, 5, false);
    checked.removeAt(proxies.size() - 1);
    checked.expectQueriesMatchScan(rng, 200);
  }
  checked.addRandom(rng, 1);
  EXPECT_LE(proxies.back(), 2 * highest) << "the rebuild reused the inner nodes it freed";
  checked.expectQueriesMatchScan(rng, 200);
}

// A rebuild whose branches run as tasks (here in reverse order, as threads may finish them) gives
// the tree the one-after-the-other build gives, node for node: queries meet the proxies in the
// same order, and the next proxies take the same ids.
TEST(DynamicTree, RebuildWithTasksBuildsTheSameTreeAsOneAfterTheOther) {
  std::mt19937 rng(11);
  CheckedTree serial;
  serial.addRandom(rng, 3000);
  DynamicTree tasked = serial.tree;
  int taskCount = 0;
  const DynamicTree::ForEachTask reversed = [&](int count, const std::function<void(int)>& task) {
    taskCount = count;
    for (int k = count - 1; k >= 0; --k) task(k);
  };
  for (int round = 0; round < 3; ++round) {
    for (size_t i = static_cast<size_t>(round); i < serial.proxies.size(); i += 2) {
      const Aabb box = randomBox(rng);
      serial.tree.setFatAabb(serial.proxies[i], box);
      tasked.setFatAabb(serial.proxies[i], box);
    }
    serial.tree.rebuild();
    tasked.rebuild(reversed);
    EXPECT_GE(taskCount, 8);
    EXPECT_EQ(tasked.height(), serial.tree.height());
    for (int q = 0; q < 100; ++q) {
      const Aabb box = randomBox(rng);
      std::vector<int> inSerial, inTasked;
      serial.tree.query(box, [&](int proxy) { inSerial.push_back(proxy); });
      tasked.query(box, [&](int proxy) { inTasked.push_back(proxy); });
      ASSERT_EQ(inTasked, inSerial);
    }
  }
  const Aabb box = randomBox(rng);
  EXPECT_EQ(tasked.createProxy(box, 0), serial.tree.createProxy(box, 0));
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
