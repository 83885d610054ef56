#include "surfcert/core/budget.hpp"

#include <limits>

namespace surfcert::core {

namespace {
thread_local bool t_active = false;
thread_local std::chrono::steady_clock::time_point t_deadline;
} // namespace

BudgetScope::BudgetScope(double ms) : saved_active_(t_active), saved_deadline_(t_deadline) {
  t_active = ms > 0;
  if (t_active)
    t_deadline = std::chrono::steady_clock::now() +
                 std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                     std::chrono::duration<double, std::milli>(ms));
}

BudgetScope::~BudgetScope() {
  t_active = saved_active_;
  t_deadline = saved_deadline_;
}

bool budget_exhausted() {
  return t_active && std::chrono::steady_clock::now() > t_deadline;
}

void check_budget() {
  if (budget_exhausted()) throw BudgetExceeded();
}

double budget_remaining_ms() {
  if (!t_active) return std::numeric_limits<double>::infinity();
  return std::chrono::duration<double, std::milli>(t_deadline - std::chrono::steady_clock::now())
      .count();
}

void check_budget_for(double estimated_ms) {
  if (!t_active) return;
  const double left = budget_remaining_ms();
  if (left <= 0 || left < estimated_ms / 4) throw BudgetExceeded();
}

} // namespace surfcert::core
