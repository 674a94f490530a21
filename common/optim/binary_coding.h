#ifndef EVOSLAM_COMMON_OPTIM_BINARY_CODING_H_
#define EVOSLAM_COMMON_OPTIM_BINARY_CODING_H_

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "common/optim/problem.h"
#include "common/util/random.h"

namespace evoslam {

// A binary chromosome: one code of `bits` bits per coordinate. Chromosomes holds one per column.
using Chromosome = Eigen::Matrix<std::uint32_t, Eigen::Dynamic, 1>;
using Chromosomes = Eigen::Matrix<std::uint32_t, Eigen::Dynamic, Eigen::Dynamic>;

// Maps the 2^bits codes of each coordinate onto its range of a box. With grid_step 0 the codes are
// spread evenly over [lower, upper], both ends included. With grid_step > 0 they map onto the grid
// points lower + k * grid_step, k = 0..K, K the last point inside the box: when codes outnumber
// points, each point gets a run of consecutive codes of equal length (within one), so random bits
// favour no point; otherwise the codes pick evenly spaced points, both ends included.
class BinaryCoding {
 public:
  BinaryCoding() = default;
  // Throws Error when bits is outside 1..30 or the grid would have 2^53 points or more.
  BinaryCoding(const Eigen::VectorXd& lower, const Eigen::VectorXd& upper, int bits,
               double grid_step);

  int bits() const { return bits_; }
  std::uint32_t max_code() const { return max_code_; }  // 2^bits - 1
  Eigen::Index dimension() const { return static_cast<Eigen::Index>(axes_.size()); }

  double Decode(Eigen::Index coordinate, std::uint32_t code) const;
  // The code whose point is nearest `value` (values outside the box count as on its edge); the
  // lower code on ties.
  std::uint32_t Encode(Eigen::Index coordinate, double value) const;

  void Decode(const Eigen::Ref<const Chromosome>& chromosome, Eigen::Ref<Eigen::VectorXd> x) const;
  Chromosome Encode(const Eigen::Ref<const Eigen::VectorXd>& x) const;
  // Every bit drawn independently, so every code is equally likely.
  Chromosome Random(Rng& rng) const;

  // The box as a dimension x 2 matrix (lower, upper): what a checkpoint needs to rebuild the
  // coding without the problem.
  Eigen::MatrixXd Box() const;

 private:
  struct Axis {
    double lower = 0.0;
    double upper = 0.0;
    double step = 0.0;       // 0: no grid
    std::uint64_t last = 0;  // K, the index of the last grid point
  };
  // The grid point a code stands for (grid axes only).
  std::uint64_t Level(const Axis& axis, std::uint32_t code) const;

  int bits_ = 0;
  std::uint32_t max_code_ = 0;
  std::vector<Axis> axes_;
};

// Decodes every column of `chromosomes` into `x` and conforms it to the problem's encoding.
void DecodeCandidates(const Problem& problem, const BinaryCoding& coding,
                      const Chromosomes& chromosomes, Eigen::MatrixXd& x);

// Chromosomes as a checkpoint stores them: doubles hold codes below 2^53 exactly.
Eigen::MatrixXd ChromosomesToMemory(const Chromosomes& chromosomes);
// Throws Error, naming the entry, when a value is not a code of `bits` bits.
Chromosomes ChromosomesFromMemory(const Eigen::MatrixXd& memory, int bits, const std::string& name);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_OPTIM_BINARY_CODING_H_
