#ifndef EVOSLAM_BENCH_PAGMO_PROBLEM_H_
#define EVOSLAM_BENCH_PAGMO_PROBLEM_H_

#include <pagmo/threading.hpp>
#include <pagmo/types.hpp>
#include <utility>

#include "common/optim/problem.h"

namespace evoslam {

// Any evoslam Problem as a pagmo user-defined problem, so that pagmo's algorithms search the very
// same fitness function as ours. pagmo evaluates one candidate per call; each call is a batch of
// one. The wrapped problem must outlive every pagmo::problem made from this.
class PagmoProblem {
 public:
  // pagmo requires user-defined problems to be default-constructible.
  PagmoProblem() = default;
  explicit PagmoProblem(const Problem& problem) : problem_(&problem) {}

  pagmo::vector_double fitness(const pagmo::vector_double& x) const;
  std::pair<pagmo::vector_double, pagmo::vector_double> get_bounds() const;
  pagmo::vector_double::size_type get_nobj() const { return problem_->objectives(); }
  // Integer and binary problems are integer in every coordinate; pagmo puts integers last.
  pagmo::vector_double::size_type get_nix() const {
    return problem_->encoding() == Encoding::kReal ? 0 : problem_->dimension();
  }
  // Problem::Evaluate is const and thread-safe by contract, so pagmo's thread islands may call
  // one copy from several threads at once.
  pagmo::thread_safety get_thread_safety() const { return pagmo::thread_safety::constant; }

 private:
  const Problem* problem_ = nullptr;
};

}  // namespace evoslam

#endif  // EVOSLAM_BENCH_PAGMO_PROBLEM_H_
