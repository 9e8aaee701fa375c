// The stackless linear quad-tree of VSSM's Alg. 2 (Bunnell 2005): the Child / Next pointers the GLSL
// computes from a node's (x, y, level) must be exactly those of the depth-first node table, so that
// following them visits every node once, in order, and ends at Null.
#include "techniques/vssm/VssmTechnique.h"

#include <gtest/gtest.h>

namespace sl
{
namespace
{

TEST(LinearQuadTree, ArithmeticPointersEqualTheDepthFirstTable)
{
  for (int height = 0; height <= 5; ++height)
  {
    const std::vector<QuadTreeNode> table = linearQuadTree(height);
    int expectedNodes = 0;
    for (int level = 0, nodesAtLevel = 1; level <= height; ++level, nodesAtLevel *= 4)
    {
      expectedNodes += nodesAtLevel;
    }
    ASSERT_EQ(static_cast<int>(table.size()), expectedNodes) << "H = " << height;
    for (const QuadTreeNode& node : table)
    {
      if (node.child >= 0)
      {
        EXPECT_EQ(quadTreeChild(node.cell), table[static_cast<std::size_t>(node.child)].cell);
      }
      else
      {
        EXPECT_EQ(node.cell.z, height) << "only leaves have no child";
      }
      const std::optional<glm::ivec3> next = quadTreeNext(node.cell);
      ASSERT_EQ(next.has_value(), node.next >= 0) << "H = " << height;
      if (next)
      {
        EXPECT_EQ(*next, table[static_cast<std::size_t>(node.next)].cell);
      }
    }
    // Always descending visits the table in order; always skipping visits the root only.
    std::optional<glm::ivec3> node = glm::ivec3(0);
    std::size_t visited = 0;
    while (node)
    {
      ASSERT_LT(visited, table.size());
      EXPECT_EQ(*node, table[visited].cell);
      ++visited;
      node = node->z < height ? quadTreeChild(*node) : quadTreeNext(*node);
    }
    EXPECT_EQ(visited, table.size());
    EXPECT_FALSE(quadTreeNext(glm::ivec3(0)).has_value());
  }
}

} // namespace
} // namespace sl
