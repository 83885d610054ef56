// Time budgets (core/budget.hpp) and their use by the batch:
// - check_budget does nothing without a scope or with budget 0, throws once the innermost
//   scope's deadline has passed, and an inner scope's end restores the outer deadline;
// - a batch line whose proof needs seconds (two tori overlapping by 1e-20: the branch and
//   bound spends its whole box budget) answers undecided with reason "budget" under
//   "budget_ms": 50, and the lines around it are answered normally, each with its time_ms;
// - two nested ellipsoids in exact mode (the offset-system route: resultants of degree 72,
//   factorisations) under "budget_ms": 50 answer undecided with reason "budget", and any bounds
//   they report contain the distance the same query certifies without a budget; the long
//   steps inside (an interpolated resultant, a factorisation judged unaffordable) stop on the
//   budget instead of running on;
// - a bad budget is an input error at its JSON path.
#include "surfcert/algebra/poly_ops.hpp"
#include "surfcert/app/scene.hpp"
#include "surfcert/core/budget.hpp"
#include "surfcert/core/rational.hpp"

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

TEST(Budget, CostModelGateRefusesOnlyWhatCannotFit) {
  EXPECT_NO_THROW(core::check_budget_for(1e12)); // no budget: every step is affordable
  core::BudgetScope minute(60000);
  EXPECT_TRUE(core::budget_remaining_ms() > 0 && core::budget_remaining_ms() <= 60000);
  EXPECT_NO_THROW(core::check_budget_for(1000));   // fits easily
  EXPECT_NO_THROW(core::check_budget_for(200000)); // 4x faster than modelled would fit
  EXPECT_THROW(core::check_budget_for(1e9), core::BudgetExceeded); // clearly cannot
}

TEST(Budget, LongResultantStopsBetweenEvaluationPoints) {
  // Two bivariate polynomials whose resultant in y is interpolated (total degrees 6 x 6).
  const core::Poly3 x = core::Poly3::variable(0), y = core::Poly3::variable(1);
  const core::Poly3 a =
      x * x * x * y * y * y + core::Poly3(3) * x * y * y + core::Poly3(7) + y * y * y * y * y * y;
  const core::Poly3 b = y * y * y * y * y * x + core::Poly3(5) * x * x * x * x * x * x -
                        core::Poly3(2) * y + core::Poly3(1);
  const core::Poly3 r = algebra::resultant(a, b, 1);
  EXPECT_FALSE(r.is_zero());
  core::BudgetScope tiny(1);
  std::this_thread::sleep_for(std::chrono::milliseconds(3));
  EXPECT_THROW(algebra::resultant(a, b, 1), core::BudgetExceeded);
}

TEST(Budget, OffsetSystemRouteStopsAndKeepsOnlyTrueBounds) {
  const std::string line = R"({"id":"n","op":"distance","mode":"exact",)"
                           R"("a":"x^2/4+y^2/9+z^2/16+x*y/7-y*z/11+x*z/13=1",)"
                           R"("b":"(x-1/10)^2+2*y^2+3*z^2+x*y/3-y*z/5+2*x*z/7+z/9=1/2")";
  const auto full = app::process_batch_line(line + "}", 1, certify::Mode::Exact);
  ASSERT_EQ(full.find("status")->text(), "certified");
  const auto* res = full.find("result");
  ASSERT_NE(res, nullptr);
  EXPECT_EQ(res->find("method")->text(), "offset_system");
  const auto lo = core::Rational::from_string(res->find("distance")->find("lower")->text());
  const auto hi = core::Rational::from_string(res->find("distance")->find("upper")->text());
  ASSERT_TRUE(lo && hi);

  const auto cut = app::process_batch_line(line + R"(,"budget_ms":50})", 2, certify::Mode::Exact);
  EXPECT_EQ(cut.find("status")->text(), "undecided");
  ASSERT_NE(cut.find("reason"), nullptr);
  EXPECT_EQ(cut.find("reason")->text(), "budget");
  // Bounds established before the stop (if any) must hold the certified distance.
  const auto* cres = cut.find("result");
  const auto* cd = cres ? cres->find("distance") : nullptr;
  if (cd && cd->find("lower")) {
    const auto l = core::Rational::from_string(cd->find("lower")->text());
    ASSERT_TRUE(l);
    EXPECT_LE(*l, *lo);
  }
  if (cd && cd->find("upper")) {
    const auto u = core::Rational::from_string(cd->find("upper")->text());
    ASSERT_TRUE(u);
    EXPECT_GE(*u, *hi);
  }
}
