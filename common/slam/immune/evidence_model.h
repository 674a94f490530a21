#ifndef EVOSLAM_COMMON_SLAM_IMMUNE_EVIDENCE_MODEL_H_
#define EVOSLAM_COMMON_SLAM_IMMUNE_EVIDENCE_MODEL_H_

// The arithmetic of paper 004's Dempster-Shafer evidence grid (§2, eqs. 1-3), shared by the grid
// and its overlays so that both score a cell with the very same operations.
//
// How the paper is read here. A reading at distance d from the laser is a simple support function
// of mass s(d) = max_belief * exp(-d / reliability_distance_m): for "occupied" in the cell a return
// ends in, for "empty" in every cell its beam crosses before that. Simple support functions for one
// hypothesis combine to 1 - prod(1 - s_i), so a cell needs only the sums
//   A_occ = sum -log(1 - s_i) over its occupied readings, and A_emp likewise,
// from which occ' = 1 - exp(-A_occ) and emp' = 1 - exp(-A_emp); Dempster's rule between the two
// (conflict K = occ' emp') then gives occ = occ'(1 - emp') / (1 - K), emp = emp'(1 - occ') / (1 -
// K).
//
// Eq. 1, f1 = sum min(1 - occ, 1 - emp), is read with occ and emp as the cell's plausibilities,
// the belief not committed against each hypothesis (Pl(occ) = 1 - emp, Pl(emp) = 1 - occ), so that
// each cell adds min(occ, emp): nothing where its readings agree, most where they contradict each
// other. Read with beliefs, eq. 1 sums what the readings leave unsure, which falls wherever more
// readings pile into fewer cells, so it rewards a trajectory that folds onto itself
// (docs/methods/immune.md measures both readings).
//
// Exactness: each reading's -log(1 - s) is rounded to a whole number of kEvidenceUnit, and the sums
// are integers, so that adding and taking back a scan are exact inverses and a cell's state does
// not hang on the order its readings came in. Everything a cell adds to the objectives is a
// deterministic function of its two integers, and f1 is counted in whole kConsistencyUnit, so
// totals kept up to date and totals recounted from scratch agree to the bit.

#include <cstdint>
#include <vector>

#include "evoslam/slam_params.pb.h"

namespace evoslam {

// Throws evoslam::Error naming the first out-of-range field ("evidence.<field>: ...").
void ValidateEvidenceGridParams(const proto::EvidenceGridParams& params);

// The unit of the evidence sums, nats: fine enough that the weakest default reading (3 m away:
// 0.025 nats, 103 units) is rounded by under 0.5 %, coarse enough that a cell's 32-bit sums take
// 1.5 million full-strength default readings (0.69 nats each) before they wrap. They wrap modulo
// 2^32, which keeps adding and taking back exact; only a cell read that often would be misjudged.
inline constexpr double kEvidenceUnit = 1.0 / 4096;

// f1 is counted in these: 2^-32 of a cell's whole contradiction, so that 2^28 cells fit in 64 bits.
inline constexpr double kConsistencyUnit = 1.0 / 4294967296.0;

// -log(1 - s) of one reading of mass s, in whole kEvidenceUnit, at least one, so that a cell
// read at all holds evidence.
std::uint32_t EvidenceUnits(double mass);

// The belief mass of one reading at `distance_m` from the laser.
double ReadingMass(const proto::EvidenceGridParams& params, double distance_m);

// The two beliefs of a cell, from its sums.
struct CellBeliefs {
  double occupied = 0;
  double empty = 0;
};

// What one cell adds to the objectives: its contradiction min(occ, emp) in kConsistencyUnit (0
// for a cell without evidence), and whether it counts as occupied (f2) or empty (f3).
struct CellScore {
  std::int64_t consistency = 0;
  bool occupied = false;
  bool empty = false;
};

// Scores cells by their sums. Holds only a threshold; the exponentials come from a table shared
// by all models.
class EvidenceScorer {
 public:
  explicit EvidenceScorer(double count_above) : count_above_(count_above) {}

  CellBeliefs Beliefs(std::uint32_t occupied_units, std::uint32_t empty_units) const;
  CellScore Score(std::uint32_t occupied_units, std::uint32_t empty_units) const;

 private:
  double count_above_;
};

// The per-grid part of the model: the empty reading's units by distance along the beam, in bins
// of 1 / kEvidenceBinsPerCell of a cell (a beam's cells are weighed by the middle of the stretch
// of beam in them).
inline constexpr int kEvidenceBinsPerCell = 8;

class EmptyWeights {
 public:
  EmptyWeights(const proto::EvidenceGridParams& params, double cell_size_m);

  // The units of an empty reading whose stretch of beam has its middle `t_cells` cells from the
  // laser (0 <= t_cells <= max range; a bit past it is clamped).
  std::uint32_t at(double t_cells) const { return View(*this).at(t_cells); }

  // The table as a value, for loops that would otherwise reload the vector's bounds after every
  // store they make.
  class View {
   public:
    explicit View(const EmptyWeights& weights)
        : units_(weights.units_.data()), last_(weights.units_.size() - 1) {}
    std::uint32_t at(double t_cells) const {
      const auto bin = static_cast<std::size_t>(t_cells * kEvidenceBinsPerCell);
      return units_[bin < last_ ? bin : last_];
    }

   private:
    const std::uint32_t* units_;
    std::size_t last_;
  };

 private:
  std::vector<std::uint32_t> units_;
};

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SLAM_IMMUNE_EVIDENCE_MODEL_H_
