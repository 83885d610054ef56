// surfcert::core budgets: a wall-time limit for one query on the current thread.
//
// A BudgetScope sets a deadline for the code it encloses on this thread (scopes nest: the
// innermost one applies, the outer one is restored at its end). Long-running loops of the
// engine (branch and bounds, refinements, root isolation) call check_budget() between steps;
// past the deadline it throws BudgetExceeded, which the query's entry point turns into an
// `undecided` answer with reason "budget" and whatever it had proven so far. Without a scope,
// check_budget() does nothing. A single library call (one FLINT resultant) is not interrupted:
// the budget is overshot by at most one such step.
// Contract for callers of check_budget(): call it only where an exception leaves no C object
// without its RAII owner (the throw unwinds through the caller).
#pragma once

#include <chrono>
#include <stdexcept>

namespace surfcert::core {

struct BudgetExceeded : std::runtime_error {
  BudgetExceeded() : std::runtime_error("time budget exhausted") {}
};

class BudgetScope {
public:
  /// A deadline `ms` milliseconds from now (ms <= 0: no limit inside this scope).
  explicit BudgetScope(double ms);
  ~BudgetScope();
  BudgetScope(const BudgetScope&) = delete;
  BudgetScope& operator=(const BudgetScope&) = delete;

private:
  bool saved_active_;
  std::chrono::steady_clock::time_point saved_deadline_;
};

/// Throws BudgetExceeded when this thread's innermost BudgetScope has run out.
void check_budget();

/// True when this thread runs under a budget that has run out (no throw).
bool budget_exhausted();

} // namespace surfcert::core
