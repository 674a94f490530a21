#ifndef EVOSLAM_COMMON_OPTIM_PROBLEM_H_
#define EVOSLAM_COMMON_OPTIM_PROBLEM_H_

#include <Eigen/Core>
#include <cstddef>
#include <span>
#include <vector>

namespace evoslam {

class Immunity;

// What values a problem's coordinates take. Algorithms search in real numbers and hand the problem
// only conforming candidates (see Conform): integers for kInteger, 0 or 1 for kBinary.
enum class Encoding { kReal, kInteger, kBinary };

// A box-bounded minimisation problem with one or more objectives, evaluated a batch at a time:
// one generation is one batch, the unit that is spread across threads and, through the service,
// across workers. Implementations must be thread-safe and deterministic: a candidate's fitness may
// not depend on the batch it arrives in.
class Problem {
 public:
  virtual ~Problem() = default;

  std::size_t dimension() const { return static_cast<std::size_t>(lower().size()); }
  virtual const Eigen::VectorXd& lower() const = 0;
  virtual const Eigen::VectorXd& upper() const = 0;
  virtual Encoding encoding() const { return Encoding::kReal; }
  virtual std::size_t objectives() const { return 1; }

  // Candidates known before the search, such as the solution as it stands, that the first
  // population should hold (as many as fit, in order), so that an elitist search cannot end
  // worse than the best of them; empty when there are none.
  virtual std::vector<Eigen::VectorXd> starts() const { return {}; }

  // Problem knowledge for the immune MOEA's vaccination; nullptr when the problem has none.
  virtual const Immunity* immunity() const { return nullptr; }

  // candidates: one column per candidate (dimension() rows). fitness: objectives() values per
  // candidate, candidate after candidate, so fitness.size() == objectives() * cols().
  virtual void Evaluate(const Eigen::Ref<const Eigen::MatrixXd>& candidates,
                        std::span<double> fitness) const = 0;
};

// Puts x into the problem's box and rounds it to its encoding.
void Conform(const Problem& problem, Eigen::Ref<Eigen::VectorXd> x);

// Throws Error when the problem cannot be searched: empty, inverted or non-finite bounds, binary
// bounds other than [0, 1], no objectives.
void ValidateProblem(const Problem& problem);

// The outcome of a single-objective search.
struct OptimResult {
  Eigen::VectorXd best;
  double best_fitness = 0.0;
  std::size_t evaluations = 0;
  std::size_t generations = 0;
};

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_OPTIM_PROBLEM_H_
