// Unit tests of the queue of stamped commands (src/scene/command_queue.*) and of the ragdoll
// name helpers (src/scene/commands.*).
#include <gtest/gtest.h>

#include "command_queue.hpp"

using namespace ragdoll_sim;
using namespace ragdoll_sim::scene;

namespace {

QueuedCommand impulseOn(const std::string& link, int64_t due_ns) {
  QueuedCommand q;
  q.due_ns = due_ns;
  ImpulseCommand c;
  c.link = link;
  q.command = c;
  return q;
}

std::string linkOf(const QueuedCommand& q) { return std::get<ImpulseCommand>(q.command).link; }

}  // namespace

TEST(CommandQueue, TakesDueCommandsByTimeThenArrival) {
  CommandQueue q;
  ASSERT_TRUE(q.push(impulseOn("c", 300)));
  ASSERT_TRUE(q.push(impulseOn("a1", 100)));
  ASSERT_TRUE(q.push(impulseOn("b", 200)));
  ASSERT_TRUE(q.push(impulseOn("a2", 100)));  // same due time as a1, arrived later
  EXPECT_EQ(q.size(), 4u);

  EXPECT_TRUE(q.takeDue(99).empty());
  std::vector<QueuedCommand> due = q.takeDue(200);
  ASSERT_EQ(due.size(), 3u);
  EXPECT_EQ(linkOf(due[0]), "a1");
  EXPECT_EQ(linkOf(due[1]), "a2");
  EXPECT_EQ(linkOf(due[2]), "b");
  EXPECT_LT(due[0].seq, due[1].seq);
  EXPECT_EQ(q.size(), 1u);
  due = q.takeDue(1000);
  ASSERT_EQ(due.size(), 1u);
  EXPECT_EQ(linkOf(due[0]), "c");
  EXPECT_EQ(q.size(), 0u);
}

TEST(CommandQueue, RefusesBeyondCapacity) {
  CommandQueue q(2);
  EXPECT_TRUE(q.push(impulseOn("a", 1)));
  EXPECT_TRUE(q.push(impulseOn("b", 2)));
  EXPECT_FALSE(q.push(impulseOn("c", 0)));
  EXPECT_FALSE(q.push(impulseOn("d", 5)));
  EXPECT_EQ(q.size(), 2u);
  EXPECT_EQ(q.dropped(), 2u);
  EXPECT_EQ(q.maxSize(), 2u);
  q.clear();
  EXPECT_TRUE(q.push(impulseOn("c", 0)));
  EXPECT_EQ(q.dropped(), 2u);
  EXPECT_EQ(q.maxSize(), 2u) << "the high-water mark stays";
}

// A flood of commands due at once (zero stamps) taken every loop iteration: the queue never
// holds more than one iteration's worth, nothing is dropped, order is arrival order.
TEST(CommandQueue, FloodDueNowIsBoundedByOneIteration) {
  CommandQueue q(64);
  int64_t now = 0;
  uint64_t taken = 0;
  std::string last;
  for (int iteration = 0; iteration < 1000; ++iteration) {
    for (int k = 0; k < 10; ++k)
      ASSERT_TRUE(q.push(impulseOn(std::to_string(iteration * 10 + k), now)));
    for (const QueuedCommand& c : q.takeDue(now)) {
      EXPECT_EQ(linkOf(c), std::to_string(taken));
      ++taken;
    }
    now += 1000000;
  }
  EXPECT_EQ(taken, 10000u);
  EXPECT_EQ(q.maxSize(), 10u);
  EXPECT_EQ(q.dropped(), 0u);
}

TEST(CommandQueue, DueTimeFromStamp) {
  const int64_t origin = 1000000000;  // stamp of sim time 0
  EXPECT_EQ(commandDueNs(0, origin, 5000), 5000) << "zero stamp: now";
  EXPECT_EQ(commandDueNs(origin + 2000, origin, 5000), 5000) << "past stamp: now";
  EXPECT_EQ(commandDueNs(origin + 9000, origin, 5000), 9000);
  EXPECT_EQ(commandDueNs(9000, 0, 5000), 9000) << "sim time: stamps are sim time";
}

TEST(RagdollNames, ValidNames) {
  EXPECT_EQ(ragdollNameError("ragdoll_2"), "");
  EXPECT_NE(ragdollNameError(""), "");
  EXPECT_NE(ragdollNameError("2nd"), "");
  EXPECT_NE(ragdollNameError("a/b"), "");
  EXPECT_NE(ragdollNameError("a-b"), "");
}

TEST(RagdollNames, SplitQualifiedName) {
  auto known = [](const std::string& n) { return n == "second"; };
  std::string ragdoll, rest;
  splitQualifiedName("second/elbow_l", known, &ragdoll, &rest);
  EXPECT_EQ(ragdoll, "second");
  EXPECT_EQ(rest, "elbow_l");
  splitQualifiedName("elbow_l", known, &ragdoll, &rest);
  EXPECT_EQ(ragdoll, "");
  EXPECT_EQ(rest, "elbow_l");
  splitQualifiedName("other/elbow_l", known, &ragdoll, &rest);  // not a ragdoll: a joint name
  EXPECT_EQ(ragdoll, "");
  EXPECT_EQ(rest, "other/elbow_l");
}
