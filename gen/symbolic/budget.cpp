// The scoped work budget of symbolic products (see budget.hpp).
#include "symbolic/budget.hpp"

namespace cgagen::symbolic {
namespace {
thread_local WorkBudget* current = nullptr;
}

WorkBudget::WorkBudget(BudgetLimits limits) : limits_(limits), outer_(current) { current = this; }

WorkBudget::~WorkBudget() { current = outer_; }

void WorkBudget::charge(std::size_t terms) {
  WorkBudget* b = current;
  if (!b) return;
  if (terms > b->limits_.max_coefficient_terms)
    throw BudgetExceeded("a product would expand one coefficient to about " + std::to_string(terms) +
                             " terms (limit " + std::to_string(b->limits_.max_coefficient_terms) + ")",
                         terms, b->limits_.max_coefficient_terms);
  b->spent_ += terms;
  if (b->spent_ > b->limits_.max_total_terms)
    throw BudgetExceeded("the statement's products expand to more than " + std::to_string(b->limits_.max_total_terms) +
                             " terms in all",
                         b->spent_, b->limits_.max_total_terms);
}

}  // namespace cgagen::symbolic
