#include "common/optim/pareto.h"
#include "common/util/infinity.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <utility>

namespace evoslam {
namespace {

// f with every column that holds a NaN replaced by +infinity, so that comparisons are total.
Eigen::MatrixXd WithoutNan(const Eigen::Ref<const Eigen::MatrixXd>& f) {
  Eigen::MatrixXd clean = f;
  for (Eigen::Index i = 0; i < clean.cols(); ++i) {
    if (clean.col(i).hasNaN()) clean.col(i).setConstant(kInfinity);
  }
  return clean;
}

// One pass over the objectives of two columns: +1 when a dominates b, -1 when b dominates a,
// 0 otherwise. Raw pointers keep the n^2 comparisons cheap in unoptimised builds too.
int CompareDominance(const double* a, const double* b, Eigen::Index objectives) {
  bool a_better = false;
  bool b_better = false;
  for (Eigen::Index k = 0; k < objectives; ++k) {
    if (a[k] < b[k]) a_better = true;
    if (b[k] < a[k]) b_better = true;
    if (a_better && b_better) return 0;
  }
  return a_better ? 1 : (b_better ? -1 : 0);
}

}  // namespace

bool ParetoRanking::Before(std::size_t a, std::size_t b) const {
  if (rank[a] != rank[b]) return rank[a] < rank[b];
  if (crowding[a] != crowding[b]) return crowding[a] > crowding[b];
  return a < b;
}

std::vector<std::size_t> ParetoRanking::Order() const {
  std::vector<std::size_t> order(size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(),
            [this](std::size_t a, std::size_t b) { return Before(a, b); });
  return order;
}

bool Dominates(const Eigen::Ref<const Eigen::VectorXd>& a,
               const Eigen::Ref<const Eigen::VectorXd>& b) {
  bool better = false;
  for (Eigen::Index k = 0; k < a.size(); ++k) {
    if (a(k) > b(k)) return false;
    if (a(k) < b(k)) better = true;
  }
  return better;
}

std::vector<std::size_t> NonDominatedRanks(const Eigen::Ref<const Eigen::MatrixXd>& f) {
  const Eigen::MatrixXd clean = WithoutNan(f);
  const auto n = static_cast<std::size_t>(clean.cols());
  // dominated[p]: the columns p dominates; count[p]: how many columns dominate p.
  std::vector<std::vector<std::size_t>> dominated(n);
  std::vector<std::size_t> count(n, 0);
  const Eigen::Index m = clean.rows();
  for (std::size_t p = 0; p < n; ++p) {
    const double* fp = clean.data() + static_cast<Eigen::Index>(p) * m;
    for (std::size_t q = p + 1; q < n; ++q) {
      const int order = CompareDominance(fp, clean.data() + static_cast<Eigen::Index>(q) * m, m);
      if (order > 0) {
        dominated[p].push_back(q);
        ++count[q];
      } else if (order < 0) {
        dominated[q].push_back(p);
        ++count[p];
      }
    }
  }
  std::vector<std::size_t> rank(n, 0);
  std::vector<std::size_t> front;
  for (std::size_t p = 0; p < n; ++p) {
    if (count[p] == 0) front.push_back(p);
  }
  for (std::size_t r = 0; !front.empty(); ++r) {
    std::vector<std::size_t> next;
    for (const std::size_t p : front) {
      rank[p] = r;
      for (const std::size_t q : dominated[p]) {
        if (--count[q] == 0) next.push_back(q);
      }
    }
    front = std::move(next);
  }
  return rank;
}

std::vector<double> CrowdingDistances(const Eigen::Ref<const Eigen::MatrixXd>& f,
                                      const std::vector<std::size_t>& rank) {
  const Eigen::MatrixXd clean = WithoutNan(f);
  const std::size_t n = rank.size();
  std::vector<double> crowding(n, 0.0);
  if (n == 0) return crowding;
  const std::size_t fronts = *std::max_element(rank.begin(), rank.end()) + 1;
  std::vector<std::vector<std::size_t>> members(fronts);
  for (std::size_t i = 0; i < n; ++i) members[rank[i]].push_back(i);
  for (std::vector<std::size_t>& front : members) {
    for (Eigen::Index k = 0; k < clean.rows(); ++k) {
      const auto value = [&](std::size_t i) { return clean(k, static_cast<Eigen::Index>(i)); };
      // Ties go by index, so equal values keep a deterministic order.
      std::sort(front.begin(), front.end(), [&](std::size_t a, std::size_t b) {
        return value(a) != value(b) ? value(a) < value(b) : a < b;
      });
      const double range = value(front.back()) - value(front.front());
      if (!(range > 0.0)) continue;
      crowding[front.front()] = kInfinity;
      crowding[front.back()] = kInfinity;
      if (!std::isfinite(range)) continue;
      for (std::size_t m = 1; m + 1 < front.size(); ++m)
        crowding[front[m]] += (value(front[m + 1]) - value(front[m - 1])) / range;
    }
  }
  return crowding;
}

ParetoRanking RankPareto(const Eigen::Ref<const Eigen::MatrixXd>& f) {
  ParetoRanking ranking;
  ranking.rank = NonDominatedRanks(f);
  ranking.crowding = CrowdingDistances(f, ranking.rank);
  return ranking;
}

std::vector<std::size_t> FirstFront(const Eigen::Ref<const Eigen::MatrixXd>& f) {
  const std::vector<std::size_t> rank = NonDominatedRanks(f);
  std::vector<std::size_t> front;
  for (std::size_t i = 0; i < rank.size(); ++i) {
    if (rank[i] == 0) front.push_back(i);
  }
  return front;
}

}  // namespace evoslam
