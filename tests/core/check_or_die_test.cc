#include "core/util/check_or_die.h"

#include <gtest/gtest.h>

namespace wavebake {
namespace {

TEST(CheckOrDieDeathTest, AbortsNamingWhoAndWhat) {
  EXPECT_DEATH(CheckOrDie("TransportRow", false, "row size differs from M"),
               "^TransportRow: row size differs from M\n");
}

TEST(CheckOrDieDeathTest, ReturnsWhenTheConditionHolds) {
  EXPECT_EXIT(
      {
        CheckOrDie("TransportRow", true, "unused");
        std::exit(7);
      },
      ::testing::ExitedWithCode(7), "");
}

}  // namespace
}  // namespace wavebake
