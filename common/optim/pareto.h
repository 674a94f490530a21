#ifndef EVOSLAM_COMMON_OPTIM_PARETO_H_
#define EVOSLAM_COMMON_OPTIM_PARETO_H_

#include <Eigen/Core>
#include <cstddef>
#include <vector>

namespace evoslam {

// Pareto ranking of candidates given as the columns of an objectives x n matrix (minimised), as in
// Deb's NSGA-II: fronts by non-dominated sorting, then crowding distance within each front. A
// column holding a NaN counts as +infinity in every objective, so a failed evaluation sits in the
// last front and never dominates anything.
struct ParetoRanking {
  std::vector<std::size_t> rank;  // front of each candidate; 0 = non-dominated
  std::vector<double> crowding;   // within the candidate's front; larger = more isolated

  std::size_t size() const { return rank.size(); }
  // The total order used for ranking-based selection: lower front first, then larger crowding
  // distance, then lower index, so that every comparison is deterministic.
  bool Before(std::size_t a, std::size_t b) const;
  // All indices, best first by Before.
  std::vector<std::size_t> Order() const;
};

// Whether column a dominates column b: no worse in every objective and better in one.
bool Dominates(const Eigen::Ref<const Eigen::VectorXd>& a,
               const Eigen::Ref<const Eigen::VectorXd>& b);

// Front ranks by Deb's fast non-dominated sort, O(objectives * n^2).
std::vector<std::size_t> NonDominatedRanks(const Eigen::Ref<const Eigen::MatrixXd>& f);

// Crowding distance of each column within its front: for every objective on which the front's
// members differ, the two extremes get +infinity and an interior member adds the gap between its
// neighbours divided by the front's range. Objectives on which a front does not differ, or whose
// range is infinite, add nothing, so a front of identical points (and every front of a single
// objective) has distance 0 throughout and falls back to index order.
std::vector<double> CrowdingDistances(const Eigen::Ref<const Eigen::MatrixXd>& f,
                                      const std::vector<std::size_t>& rank);

ParetoRanking RankPareto(const Eigen::Ref<const Eigen::MatrixXd>& f);

// Indices of the non-dominated columns, ascending.
std::vector<std::size_t> FirstFront(const Eigen::Ref<const Eigen::MatrixXd>& f);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_OPTIM_PARETO_H_
