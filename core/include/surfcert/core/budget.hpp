// surfcert::core budgets: a wall-time limit for one query on the current thread.
//
// A BudgetScope sets a deadline for the code it encloses on this thread (scopes nest: the
// innermost one applies, the outer one is restored at its end). Long-running loops of the
// engine (branch and bounds, refinements, root isolation) call check_budget() between steps;
// past the deadline it throws BudgetExceeded, which the query's entry point turns into an
// `undecided` answer with reason "budget" and whatever it had proven so far. Without a scope,
// check_budget() does nothing. A single library call (one FLINT factorisation) is not
// interrupted; before one that can run long, the caller states its estimated cost
// (check_budget_for) and the query stops when the remaining time clearly cannot cover it, so
// the budget is overshot by at most one step the cost model judged affordable.
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

/// Milliseconds left before this thread's innermost deadline (infinity without a budget, <= 0
/// once it has passed).
double budget_remaining_ms();

/// Before a step that cannot be interrupted and is estimated (from a cost model measured on
/// the development machine) to take `estimated_ms`: throws BudgetExceeded when the budget has
/// run out or when even at four times the modelled speed the step would not finish in time
/// (the models are good to a factor of a few; "clearly cannot" keeps affordable steps).
void check_budget_for(double estimated_ms);

} // namespace surfcert::core
