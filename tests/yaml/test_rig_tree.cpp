// The rig text's tree (yaml/rig_tree.h): the last file text parsed on a thread is kept, so a
// sweep's points parse it once; what comes back must still be the text's own tree, a copy.
#include <gtest/gtest.h>

#include "yaml/rig_tree.h"

namespace metrosync {
namespace {

TEST(RigTree, TheKeptTreeIsACopyOfTheSameText) {
  const std::string a = "platform:\n  mass: 1.5\nmetronomes:\n  - {A: 0.3}\n  - {A: 0.4}\n";
  const std::string b = "platform:\n  mass: 2.5\n";
  Node first = parseTree(a, 0);
  ASSERT_EQ(first.kind, Node::Kind::Map);
  first.find("platform")->find("mass")->scalar = "changed";  // the caller's copy only
  const Node again = parseTree(a, 0);
  EXPECT_EQ(again.find("platform")->find("mass")->scalar, "1.5");
  ASSERT_EQ(again.find("metronomes")->seq.size(), 2u);
  EXPECT_EQ(again.find("metronomes")->seq[1].find("A")->scalar, "0.4");
  EXPECT_EQ(again.find("metronomes")->seq[1].at.line, 5);
  // another text, and an override's value in between, give their own trees
  EXPECT_EQ(parseTree("7", 1).scalar, "7");
  EXPECT_EQ(parseTree(b, 0).find("platform")->find("mass")->scalar, "2.5");
  EXPECT_EQ(parseTree(a, 0).find("platform")->find("mass")->scalar, "1.5");
}

TEST(RigTree, ABadTextFailsEveryTime) {
  const std::string bad = "platform: [1, 2\n";
  for (int k = 0; k < 2; ++k) EXPECT_THROW(parseTree(bad, 0), TreeError);
  EXPECT_EQ(parseTree("x: 1\n", 0).find("x")->scalar, "1");
}

}  // namespace
}  // namespace metrosync
