// The naming rule (src/scene/names.hpp): ragdoll (and later object) names are one ROS graph name
// token of at most 128 characters, TF prefixes are such tokens joined by '/'; a refusal states
// the rule and never echoes a huge name whole. The Scene refuses a bad name in addRagdoll.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "names.hpp"
#include "ragdoll_sim/scene.hpp"
#include "scene_views.hpp"

using namespace ragdoll_sim;
using namespace ragdoll_sim::scene;

namespace {

const std::string kRuleWords = "a letter first";

SpawnDef stick(const std::string& name) {
  SpawnDef s;
  s.name = name;
  s.def = test::stickModel();
  s.pose = Transform(Vec3(0, 0, 1), Quat::Identity());
  return s;
}

}  // namespace

TEST(Names, ValidNames) {
  for (const std::string n : {"a", "ragdoll_2", "Bob", "x_", "A1_b2"})
    EXPECT_EQ(ragdollNameError(n), "") << n;
  EXPECT_EQ(ragdollNameError(std::string(kMaxNameLength, 'a')), "");
  EXPECT_EQ(nameError("crate_1", "object name"), "");
}

TEST(Names, BadCharactersAreRefusedWithTheRule) {
  for (const std::string n : {"", "2nd", "_a", "a-b", "a/b", "/a", "~a", "a b", "a.b", "a\n",
                              "\xc3\xa4pfel"}) {
    const std::string e = ragdollNameError(n);
    EXPECT_NE(e, "") << "'" << n << "'";
    EXPECT_NE(e.find(kRuleWords), std::string::npos) << e;
    EXPECT_NE(e.find("128"), std::string::npos) << e;
  }
  EXPECT_NE(ragdollNameError("2nd").find("starts with a digit"), std::string::npos);
  EXPECT_NE(ragdollNameError("a-b").find("'-'"), std::string::npos);
  EXPECT_NE(nameError("a-b", "object name").find("object name 'a-b'"), std::string::npos);
}

TEST(Names, TooLongIsRefusedWithoutEchoingTheName) {
  const std::string e = ragdollNameError(std::string(kMaxNameLength + 1, 'a'));
  EXPECT_NE(e.find("too long"), std::string::npos) << e;
  EXPECT_NE(e.find(kRuleWords), std::string::npos) << e;
  const std::string huge(1000000, 'a');
  const std::string h = ragdollNameError(huge);
  EXPECT_NE(h, "");
  EXPECT_LT(h.size(), 300u) << h.substr(0, 300);
  EXPECT_NE(h.find("1000000 characters"), std::string::npos) << h;
  EXPECT_LT(tfPrefixError(huge).size(), 400u);
}

TEST(Names, Quoted) {
  EXPECT_EQ(quoted("bob"), "'bob'");
  const std::string q = quoted(std::string(1000, 'x'));
  EXPECT_EQ(q, "'" + std::string(48, 'x') + "...' (1000 characters)");
}

TEST(Names, TfPrefixes) {
  for (const std::string& p : std::vector<std::string>{"", "sim", "robots/bob", "a/b_2/C",
                                                       std::string(kMaxTfPrefixLength, 'a')})
    EXPECT_EQ(tfPrefixError(p), "") << p;
  for (const std::string& p :
       std::vector<std::string>{"/bob", "bob/", "a//b", "a-b", "robots/2bob", "a b", "~bob", "/",
                                std::string(kMaxTfPrefixLength + 1, 'a')}) {
    const std::string e = tfPrefixError(p);
    EXPECT_NE(e, "") << p;
    EXPECT_NE(e.find("joined by single '/'"), std::string::npos) << e;
  }
}

TEST(Names, SceneRefusesABadName) {
  Scene scene{SceneDef()};
  std::string e;
  EXPECT_EQ(scene.addRagdoll(stick(std::string(1000, 'a')), &e), SpawnResult::BadName);
  EXPECT_NE(e.find(kRuleWords), std::string::npos) << e;
  EXPECT_LT(e.size(), 300u);
  EXPECT_EQ(scene.addRagdoll(stick(""), &e), SpawnResult::BadName);
  ASSERT_EQ(scene.addRagdoll(stick("a"), &e), SpawnResult::Added) << e;
  ASSERT_TRUE(scene.start(&e)) << e;
  EXPECT_EQ(scene.addRagdoll(stick("b-c"), &e), SpawnResult::BadName);
  EXPECT_EQ(scene.ragdollCount(), 1u);
  EXPECT_EQ(scene.world().bodyCount(), 3) << "ground and two links: nothing of the refused one";
}
