#ifndef EVOSLAM_COMMON_LOCALIZATION_SCAN_FITNESS_H_
#define EVOSLAM_COMMON_LOCALIZATION_SCAN_FITNESS_H_

#include <cstddef>
#include <span>
#include <string_view>
#include <vector>

#include "common/sensor/laser_scan.h"

namespace evoslam {

// The two matching strategies of Moravec's estimator, both minimised here:
// F3: sum over beams of |simulated - observed| (L1, point to point), each beam's term optionally
//     capped;
// F2: minus the number of beams whose difference lies within the sensor's tolerance.
// Beams the observation has no return for, and beams the simulation finds no wall for within
// range, are left out of both.
enum class FitnessKind { kF3, kF2 };
FitnessKind ParseFitnessKind(std::string_view name);  // "f3" | "f2"
std::string_view FitnessKindName(FitnessKind kind);

struct FitnessParams {
  FitnessKind kind = FitnessKind::kF3;
  // F2's tolerance grows linearly with range: base + slope * (simulated + observed). The defaults
  // are the linearised accuracy of a SICK scanner used by the papers (1 cm + 59/6000 per metre).
  double f2_base = 0.01;
  double f2_slope = 59.0 / 6000.0;
  // F3 counts each beam's difference up to this many metres; 0 leaves it uncapped, as the papers
  // do. A cap keeps a few beams that meet what the map lacks (people, doors, a grid's ragged
  // walls at grazing angles) from outweighing the rest of the scan.
  double f3_cap = 0.0;
};

// How the observed beams line up with a fan of simulated rays: beam j of heading shift k reads
// ray k * shift_stride + j * beam_stride. One simulated fan therefore serves every heading in the
// window (the cyclic shifts of the papers' full-circle scan).
struct ShiftLayout {
  std::size_t shifts = 1;
  std::size_t shift_stride = 1;
  std::size_t beam_stride = 1;
  double ray_step = 0.0;      // angle between neighbouring rays
  double first_offset = 0.0;  // angle of ray 0 relative to the window's centre heading
  std::size_t rays = 0;       // rays in the fan

  double shift_angle(std::size_t k) const;  // heading of shift k relative to the centre heading
};

// Chooses the ray spacing so that both the beam spacing and the heading step are whole numbers
// of rays: heading_step is honoured exactly when it divides the beam spacing or is a multiple of
// it, and otherwise rounded to the nearest such value.
ShiftLayout MakeShiftLayout(const LaserScan& scan, double heading_half_window, double heading_step);

// The observed scan, reduced to the beams that returned, ready for matching.
struct ObservedBeams {
  std::vector<std::size_t> index;  // beam number in the scan
  std::vector<float> range;
};
ObservedBeams PrepareObservation(const LaserScan& scan, float max_range);

struct ShiftScore {
  double fitness = 0.0;
  std::size_t shift = 0;
};

// Scores every heading shift of `layout` against the simulated fan `rays` and returns the best;
// ties go to the shift nearest the centre of the window. `scratch` needs layout.shifts floats.
ShiftScore BestShift(const FitnessParams& params, const ShiftLayout& layout,
                     const ObservedBeams& observed, std::span<const float> rays, float max_range,
                     std::span<float> scratch);

// Scores one heading: rays[i] is the simulated range of the scan's beam i.
double ScoreAligned(const FitnessParams& params, const ObservedBeams& observed,
                    std::span<const float> rays, float max_range);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_LOCALIZATION_SCAN_FITNESS_H_
