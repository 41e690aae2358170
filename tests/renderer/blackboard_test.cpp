#include "features/context/blackboard.hpp"

#include <gtest/gtest.h>

namespace fgb::features {
namespace {

struct Lists {
  int counts = 0;
};
struct Other {
  float value = 0.0f;
};

TEST(Blackboard, StoresOneEntryPerType) {
  Blackboard board;
  EXPECT_TRUE(board.empty());
  board.set(Lists{3});
  board.set(Other{1.5f});
  EXPECT_EQ(board.get<Lists>().counts, 3);
  EXPECT_FLOAT_EQ(board.get<Other>().value, 1.5f);
  board.set(Lists{7});  // replaces
  EXPECT_EQ(board.get<Lists>().counts, 7);
}

TEST(Blackboard, MissingEntryIsReportedNotDefaulted) {
  Blackboard board;
  EXPECT_EQ(board.find<Lists>(), nullptr);
  EXPECT_THROW((void)board.get<Lists>(), std::logic_error);
}

TEST(Blackboard, GetReturnsAReferenceToTheStoredEntry) {
  Blackboard board;
  board.set(Lists{1});
  board.get<Lists>().counts = 42;
  const Blackboard& view = board;
  EXPECT_EQ(view.get<Lists>().counts, 42);
}

}  // namespace
}  // namespace fgb::features
