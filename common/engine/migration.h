#ifndef EVOSLAM_COMMON_ENGINE_MIGRATION_H_
#define EVOSLAM_COMMON_ENGINE_MIGRATION_H_

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "common/optim/algorithm.h"
#include "common/util/random.h"

namespace evoslam {

// Who sends migrants to whom. Ring: island i receives from i - 1; bidirectional ring: from both
// neighbours (pagmo's ring). Star: island 0 is the hub, exchanging with every other island.
// Random: every epoch each island receives from one other island drawn at random.
enum class Topology { kRing, kBidirectionalRing, kFullyConnected, kStar, kRandom };
// ring | bidirectional-ring | fully-connected | star | random
Topology ParseTopology(std::string_view name);
std::string_view TopologyName(Topology topology);

// best-replace-worst: an island sends its k best; the receiver's worst give way to immigrants
// that are better than them. random-replace: k random individuals replace k random residents.
enum class MigrationPolicy { kBestReplaceWorst, kRandomReplace };
MigrationPolicy ParseMigrationPolicy(std::string_view name);
std::string_view MigrationPolicyName(MigrationPolicy policy);

struct MigrationParams {
  std::size_t interval = 10;  // generations between migrations
  std::size_t migrants = 1;   // sent by each island per migration
  Topology topology = Topology::kRing;
  MigrationPolicy policy = MigrationPolicy::kBestReplaceWorst;
};

void ValidateMigrationParams(const MigrationParams& params, std::size_t population);

// Candidates in transit, as columns.
struct Migrants {
  Eigen::MatrixXd x;
  Eigen::MatrixXd f;
  std::size_t size() const { return static_cast<std::size_t>(x.cols()); }
};

// Indices of the population from best to worst: by fitness for one objective (NaN last), by
// Pareto rank and crowding for several; ties by index.
std::vector<std::size_t> QualityOrder(const Eigen::MatrixXd& f);

// For each island, the islands it receives from this epoch (random topology draws from rng).
std::vector<std::vector<std::size_t>> MigrationSources(Topology topology, std::size_t islands,
                                                       Rng& rng);

Migrants SelectEmigrants(const Population& population, const MigrationParams& params, Rng& rng);

// Puts immigrants into the algorithm's population according to the policy.
void Immigrate(Algorithm& algorithm, const Migrants& immigrants, MigrationPolicy policy, Rng& rng);

// Several senders' migrants side by side.
Migrants Concatenate(const std::vector<Migrants>& parts);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_ENGINE_MIGRATION_H_
