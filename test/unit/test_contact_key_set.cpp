// The broad phase's set of contact keys must agree with std::set through any mix of inserts and
// erases, including erases that shift a run of keys back across the end of the table.
#include <gtest/gtest.h>

#include <random>
#include <set>

#include "contact.hpp"
#include "contact_key_set.hpp"

namespace impulse2d {
namespace {

TEST(ContactKeySet, AgreesWithStdSetThroughRandomInsertsAndErases) {
  std::mt19937_64 rng(7);
  // Few bodies, so that keys repeat and runs of probes grow long.
  std::uniform_int_distribution<int> body(0, 60), shape(0, 3), op(0, 2);
  ContactKeySet keys;
  std::set<uint64_t> reference;
  for (int i = 0; i < 200000; ++i) {
    int a = body(rng), b = body(rng);
    if (a == b) continue;
    if (a > b) std::swap(a, b);
    const uint64_t key = contactKey(a, shape(rng), b, shape(rng));
    switch (op(rng)) {
      case 0:
        ASSERT_EQ(keys.insert(key), reference.insert(key).second) << "step " << i;
        break;
      case 1:
        keys.erase(key);
        reference.erase(key);
        break;
      default:
        ASSERT_EQ(keys.contains(key), reference.count(key) == 1) << "step " << i;
    }
    ASSERT_EQ(keys.size(), reference.size()) << "step " << i;
  }
  for (const uint64_t key : reference) EXPECT_TRUE(keys.contains(key));
  keys.clear();
  EXPECT_EQ(keys.size(), 0u);
  for (const uint64_t key : reference) EXPECT_FALSE(keys.contains(key));
}

TEST(ContactKeySet, ErasingEveryKeyLeavesNoneBehindAtAnySize) {
  for (int count : {1, 31, 32, 33, 1000}) {
    ContactKeySet keys;
    for (int i = 0; i < count; ++i) ASSERT_TRUE(keys.insert(contactKey(i, 0, i + 1, 0)));
    for (int i = 0; i < count; ++i) ASSERT_FALSE(keys.insert(contactKey(i, 0, i + 1, 0)));
    for (int i = count - 1; i >= 0; i -= 2) keys.erase(contactKey(i, 0, i + 1, 0));
    for (int i = 0; i < count; ++i) {
      EXPECT_EQ(keys.contains(contactKey(i, 0, i + 1, 0)), (count - 1 - i) % 2 == 1) << i;
    }
    for (int i = 0; i < count; ++i) keys.erase(contactKey(i, 0, i + 1, 0));
    EXPECT_EQ(keys.size(), 0u) << count;
    EXPECT_FALSE(keys.contains(contactKey(0, 0, 1, 0)));
  }
}

}  // namespace
}  // namespace impulse2d
