// The expander's work budget: how many terms symbolic products may expand to, so that no script can make
// cgagen run for minutes or exhaust memory. Products charge the scoped WorkBudget of their thread with the
// number of terms they are about to expand (an estimate made before expanding: the product of the
// factors' term counts); past a limit they throw BudgetExceeded, which the expander turns into a located
// error naming the statement. Counting terms rather than time keeps the verdict the same on every machine.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>

namespace cgagen::symbolic {

struct BudgetLimits {
  // One coefficient of one product. The largest in the bundled scripts is a few hundred terms.
  std::size_t max_coefficient_terms = 20000;
  // All products of one statement together (a script of many statements may spend this on each). The bundled
  // scripts stay below 5000.
  std::size_t max_total_terms = 100000;
};

class BudgetExceeded : public std::runtime_error {
 public:
  BudgetExceeded(const std::string& what, std::size_t terms, std::size_t limit)
      : std::runtime_error(what), terms_(terms), limit_(limit) {}
  std::size_t terms() const { return terms_; }
  std::size_t limit() const { return limit_; }

 private:
  std::size_t terms_, limit_;
};

// While one is alive, the thread's symbolic products are charged to it (the innermost one, when nested).
// Without one, products are not limited.
class WorkBudget {
 public:
  explicit WorkBudget(BudgetLimits limits = {});
  ~WorkBudget();
  WorkBudget(const WorkBudget&) = delete;
  WorkBudget& operator=(const WorkBudget&) = delete;

  std::size_t spent() const { return spent_; }
  const BudgetLimits& limits() const { return limits_; }

  // Charges `terms` terms of one coefficient to the current budget, if any; throws BudgetExceeded.
  static void charge(std::size_t terms);

 private:
  BudgetLimits limits_;
  std::size_t spent_ = 0;
  WorkBudget* outer_;
};

}  // namespace cgagen::symbolic
