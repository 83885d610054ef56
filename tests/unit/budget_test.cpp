// Time budgets (core/budget.hpp) and their use by the batch:
// - check_budget does nothing without a scope or with budget 0, throws once the innermost
//   scope's deadline has passed, and an inner scope's end restores the outer deadline;
// - a batch line whose proof needs seconds (two tori overlapping by 1e-20: the branch and
//   bound spends its whole box budget) answers undecided with reason "budget" under
//   "budget_ms": 50, and the lines around it are answered normally, each with its time_ms;
// - a bad budget is an input error at its JSON path.
#include "surfcert/app/scene.hpp"
#include "surfcert/core/budget.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

using namespace surfcert;

TEST(Budget, ScopesNestAndExpire) {
  EXPECT_NO_THROW(core::check_budget());
  {
    core::BudgetScope none(0);
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
    EXPECT_NO_THROW(core::check_budget());
  }
  core::BudgetScope outer(60000);
  EXPECT_NO_THROW(core::check_budget());
  {
    core::BudgetScope inner(1);
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    EXPECT_TRUE(core::budget_exhausted());
    EXPECT_THROW(core::check_budget(), core::BudgetExceeded);
  }
  EXPECT_NO_THROW(core::check_budget()); // the outer minute is back
}

TEST(Budget, SlowLineAnswersUndecidedWithReasonBudget) {
  const std::string a =
      R"({"type":"torus","center":[0,0,0],"axis":[0,0,1],"major_radius":3,"minor_radius":1})";
  const std::string b =
      R"({"type":"torus","center":["799999999999999999999/100000000000000000000",)"
      R"(0,0],"axis":[0,0,1],"major_radius":3,"minor_radius":1})";
  const std::string slow =
      R"({"id":"slow","op":"distance","a":)" + a + R"(,"b":)" + b + R"(,"budget_ms":50})";
  const auto r = app::process_batch_line(slow, 1, certify::Mode::Filtered);
  EXPECT_EQ(r.find("status")->text(), "undecided");
  ASSERT_NE(r.find("reason"), nullptr);
  EXPECT_EQ(r.find("reason")->text(), "budget");
  ASSERT_NE(r.find("time_ms"), nullptr);
  // The batch-wide default applies when the line has none; the line's own value overrides.
  const std::string plain = R"({"id":2,"op":"distance","a":)" + a + R"(,"b":)" + b + "}";
  const auto d = app::process_batch_line(plain, 2, certify::Mode::Filtered, nullptr, 50);
  EXPECT_EQ(d.find("reason")->text(), "budget");
  // A fast line under the same budget is answered normally.
  const auto f = app::process_batch_line(
      R"({"id":3,"op":"distance","a":"x^2+y^2+z^2=1","b":"(x-3)^2+y^2+z^2=1"})", 3,
      certify::Mode::Filtered, nullptr, 50);
  EXPECT_EQ(f.find("status")->text(), "certified");
  EXPECT_EQ(f.find("reason"), nullptr);
  ASSERT_NE(f.find("time_ms"), nullptr);
}

TEST(Budget, BadBudgetIsAnInputError) {
  const auto r = app::process_batch_line(
      R"({"id":1,"op":"classify","a":"x^2+y^2+z^2=1","b":"x^2+y^2=1/4","budget_ms":-5})", 1,
      certify::Mode::Filtered);
  EXPECT_EQ(r.find("status")->text(), "error");
  EXPECT_EQ(r.find("error")->find("json_path")->text(), "$.budget_ms");
}
