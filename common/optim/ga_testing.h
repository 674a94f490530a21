#ifndef EVOSLAM_COMMON_OPTIM_GA_TESTING_H_
#define EVOSLAM_COMMON_OPTIM_GA_TESTING_H_

// Helpers shared by the SGA and aGA tests (header-only; test binaries include it).

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <vector>

#include "common/optim/ga_params.h"
#include "common/optim/optim_testing.h"

namespace evoslam::testing {

// 003's localization setting: a 60 x 60 cm window searched on a 1 cm grid, with the minimum (a
// cone) at a grid point off the window's centre. Counts the candidates it receives that are outside
// the window or off the grid.
class GridWindowProblem : public Problem {
 public:
  static constexpr double kHalfWidth = 0.3;
  static constexpr double kStep = 0.01;

  const Eigen::VectorXd& lower() const override { return lower_; }
  const Eigen::VectorXd& upper() const override { return upper_; }
  void Evaluate(const Eigen::Ref<const Eigen::MatrixXd>& candidates,
                std::span<double> fitness) const override {
    for (Eigen::Index i = 0; i < candidates.cols(); ++i) {
      const auto x = candidates.col(i);
      for (Eigen::Index j = 0; j < 2; ++j) {
        const double k = (x(j) + kHalfWidth) / kStep;
        if (std::abs(x(j)) > kHalfWidth || std::abs(k - std::round(k)) > 1e-6) ++off_grid_;
      }
      fitness[static_cast<std::size_t>(i)] = (x - minimum_).norm();
    }
  }

  const Eigen::Vector2d& minimum() const { return minimum_; }
  int off_grid() const { return off_grid_; }

 private:
  Eigen::VectorXd lower_ = Eigen::VectorXd::Constant(2, -kHalfWidth);
  Eigen::VectorXd upper_ = Eigen::VectorXd::Constant(2, kHalfWidth);
  Eigen::Vector2d minimum_{0.07, -0.12};
  mutable std::atomic<int> off_grid_{0};
};

// The GA parameters of 003's localization: the defaults on the 1 cm grid.
inline GaParams WindowParams() {
  GaParams params;
  params.grid_step = GridWindowProblem::kStep;
  return params;
}

// How many of `seeds` runs of `generations` generations end within 1 cm of the minimum; every
// candidate must have been inside the window and on its grid.
template <typename Ga>
int RunsFindingTheWindowMinimum(const GaParams& params, std::size_t generations, int seeds) {
  const GridWindowProblem problem;
  int found = 0;
  for (int seed = 1; seed <= seeds; ++seed) {
    Ga ga(params);
    const OptimResult r = RunFor(problem, ga, generations, static_cast<std::uint64_t>(seed));
    if ((r.best - problem.minimum()).norm() <= 0.01 + 1e-9) ++found;
  }
  EXPECT_EQ(problem.off_grid(), 0);
  return found;
}

// The best fitness of runs from seeds first, first + 1, ...
template <typename Ga>
std::vector<double> BestFitnesses(const Problem& problem, const GaParams& params,
                                  std::size_t generations, int seeds, int first = 1) {
  std::vector<double> best;
  for (int seed = first; seed < first + seeds; ++seed) {
    Ga ga(params);
    best.push_back(RunFor(problem, ga, generations, static_cast<std::uint64_t>(seed)).best_fitness);
  }
  return best;
}

inline int RunsBelow(const std::vector<double>& best, double threshold) {
  return static_cast<int>(
      std::count_if(best.begin(), best.end(), [&](double f) { return f < threshold; }));
}

inline double Mean(const std::vector<double>& values) {
  double sum = 0.0;
  for (const double v : values) sum += v;
  return sum / static_cast<double>(values.size());
}

inline double Median(std::vector<double> values) {
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

// Root-mean-square distance of the population from its centroid.
inline double Spread(const Algorithm& algorithm) {
  const Eigen::MatrixXd& x = algorithm.population().x;
  const Eigen::VectorXd centroid = x.rowwise().mean();
  return (x.colwise() - centroid).norm() / std::sqrt(static_cast<double>(x.cols()));
}

// The population's spread after `generations` generations, averaged over seeds 1..seeds.
template <typename Ga>
double MeanSpread(const Problem& problem, const GaParams& params, std::size_t generations,
                  int seeds) {
  double total = 0.0;
  for (int seed = 1; seed <= seeds; ++seed) {
    Ga ga(params);
    RunFor(problem, ga, generations, static_cast<std::uint64_t>(seed));
    total += Spread(ga);
  }
  return total / seeds;
}

}  // namespace evoslam::testing

#endif  // EVOSLAM_COMMON_OPTIM_GA_TESTING_H_
