#include "common/engine/migration.h"

#include <algorithm>
#include <numeric>

#include "common/optim/pareto.h"
#include "common/util/error.h"

namespace evoslam {

Topology ParseTopology(std::string_view name) {
  if (name == "ring") return Topology::kRing;
  if (name == "bidirectional-ring") return Topology::kBidirectionalRing;
  if (name == "fully-connected") return Topology::kFullyConnected;
  if (name == "star") return Topology::kStar;
  if (name == "random") return Topology::kRandom;
  throw Error("unknown topology '" + std::string(name) +
              "' (expected ring, bidirectional-ring, fully-connected, star or random)");
}

std::string_view TopologyName(Topology topology) {
  switch (topology) {
    case Topology::kRing:
      return "ring";
    case Topology::kBidirectionalRing:
      return "bidirectional-ring";
    case Topology::kFullyConnected:
      return "fully-connected";
    case Topology::kStar:
      return "star";
    case Topology::kRandom:
      return "random";
  }
  return "unknown";
}

MigrationPolicy ParseMigrationPolicy(std::string_view name) {
  if (name == "best-replace-worst") return MigrationPolicy::kBestReplaceWorst;
  if (name == "random-replace") return MigrationPolicy::kRandomReplace;
  throw Error("unknown migration policy '" + std::string(name) +
              "' (expected best-replace-worst or random-replace)");
}

std::string_view MigrationPolicyName(MigrationPolicy policy) {
  return policy == MigrationPolicy::kBestReplaceWorst ? "best-replace-worst" : "random-replace";
}

void ValidateMigrationParams(const MigrationParams& params, std::size_t population) {
  if (params.interval == 0) throw Error("migration interval must be at least 1 generation");
  if (params.migrants >= population) {
    throw Error("migration: " + std::to_string(params.migrants) +
                " migrants would replace a whole population of " + std::to_string(population) +
                " (use fewer than the population)");
  }
}

std::vector<std::size_t> QualityOrder(const Eigen::MatrixXd& f) {
  return f.rows() > 1 ? RankPareto(f).Order() : RankByFitness(f);
}

std::vector<std::vector<std::size_t>> MigrationSources(Topology topology, std::size_t islands,
                                                       Rng& rng) {
  std::vector<std::vector<std::size_t>> sources(islands);
  if (islands < 2) return sources;
  for (std::size_t i = 0; i < islands; ++i) {
    switch (topology) {
      case Topology::kRing:
        sources[i] = {(i + islands - 1) % islands};
        break;
      case Topology::kBidirectionalRing:
        sources[i] = {(i + islands - 1) % islands};
        // With two islands both neighbours are the same island, which sends once.
        if (islands > 2) sources[i].push_back((i + 1) % islands);
        break;
      case Topology::kFullyConnected:
        for (std::size_t j = 0; j < islands; ++j) {
          if (j != i) sources[i].push_back(j);
        }
        break;
      case Topology::kStar:
        if (i == 0) {
          for (std::size_t j = 1; j < islands; ++j) sources[i].push_back(j);
        } else {
          sources[i] = {0};
        }
        break;
      case Topology::kRandom: {
        const std::size_t j = rng.UniformIndex(islands - 1);
        sources[i] = {j < i ? j : j + 1};
        break;
      }
    }
  }
  return sources;
}

Migrants SelectEmigrants(const Population& population, const MigrationParams& params, Rng& rng) {
  const std::size_t n = population.size();
  const std::size_t k = std::min(params.migrants, n);
  std::vector<std::size_t> chosen;
  if (params.policy == MigrationPolicy::kBestReplaceWorst) {
    chosen = QualityOrder(population.f);
    chosen.resize(k);
  } else {
    std::vector<std::size_t> all(n);
    std::iota(all.begin(), all.end(), std::size_t{0});
    for (std::size_t m = 0; m < k; ++m) {
      std::swap(all[m], all[m + rng.UniformIndex(n - m)]);
      chosen.push_back(all[m]);
    }
  }
  Migrants out;
  out.x.resize(population.x.rows(), static_cast<Eigen::Index>(k));
  out.f.resize(population.f.rows(), static_cast<Eigen::Index>(k));
  for (std::size_t m = 0; m < k; ++m) {
    out.x.col(static_cast<Eigen::Index>(m)) =
        population.x.col(static_cast<Eigen::Index>(chosen[m]));
    out.f.col(static_cast<Eigen::Index>(m)) =
        population.f.col(static_cast<Eigen::Index>(chosen[m]));
  }
  return out;
}

void Immigrate(Algorithm& algorithm, const Migrants& immigrants, MigrationPolicy policy, Rng& rng) {
  const Population& residents = algorithm.population();
  const std::size_t n = residents.size();
  if (immigrants.size() == 0 || n == 0) return;
  if (immigrants.x.rows() != residents.x.rows() || immigrants.f.rows() != residents.f.rows())
    throw Error("migration: immigrants do not match the island's problem");

  if (policy == MigrationPolicy::kRandomReplace) {
    // The island's best never gives way, so a random migration cannot lose the island's champion.
    const std::size_t best = QualityOrder(residents.f).front();
    std::vector<std::size_t> slots;
    for (std::size_t i = 0; i < n; ++i) {
      if (i != best) slots.push_back(i);
    }
    const std::size_t k = std::min(immigrants.size(), slots.size());
    for (std::size_t m = 0; m < k; ++m) {
      std::swap(slots[m], slots[m + rng.UniformIndex(slots.size() - m)]);
      algorithm.Replace(slots[m], immigrants.x.col(static_cast<Eigen::Index>(m)),
                        immigrants.f.col(static_cast<Eigen::Index>(m)));
    }
    return;
  }

  // Rank residents and immigrants together and keep the best n: the immigrants that make the cut
  // take the places of the residents that do not. Residents come first, so they win ties.
  Eigen::MatrixXd all_f(residents.f.rows(), static_cast<Eigen::Index>(n + immigrants.size()));
  all_f << residents.f, immigrants.f;
  const std::vector<std::size_t> order = QualityOrder(all_f);
  std::vector<bool> kept(n + immigrants.size(), false);
  for (std::size_t r = 0; r < n; ++r) kept[order[r]] = true;
  std::vector<std::size_t> leaving;
  for (std::size_t i = 0; i < n; ++i) {
    if (!kept[i]) leaving.push_back(i);
  }
  std::size_t next = 0;
  for (std::size_t r = 0; r < n; ++r) {
    if (order[r] < n) continue;
    const auto m = static_cast<Eigen::Index>(order[r] - n);
    algorithm.Replace(leaving[next++], immigrants.x.col(m), immigrants.f.col(m));
  }
}

Migrants Concatenate(const std::vector<Migrants>& parts) {
  Migrants out;
  Eigen::Index cols = 0;
  for (const Migrants& p : parts) cols += p.x.cols();
  if (parts.empty()) return out;
  out.x.resize(parts.front().x.rows(), cols);
  out.f.resize(parts.front().f.rows(), cols);
  Eigen::Index at = 0;
  for (const Migrants& p : parts) {
    out.x.middleCols(at, p.x.cols()) = p.x;
    out.f.middleCols(at, p.f.cols()) = p.f;
    at += p.x.cols();
  }
  return out;
}

}  // namespace evoslam
