#ifndef EVOSLAM_COMMON_SIM_LASER_MODEL_H_
#define EVOSLAM_COMMON_SIM_LASER_MODEL_H_

namespace evoslam {

// The simulated range finder. The defaults are those of a SICK PLS-100: 361 beams spread
// evenly over 180 degrees with both ends included, from -90 degrees (right) to +90 (left).
struct LaserModel {
  int beams = 361;
  double field_of_view_deg = 180.0;
  double max_range = 8.0;  // metres; a beam meeting no wall within it reads max_range
  double min_range = 0.0;

  double angle_min() const;        // radians, robot frame: -field_of_view / 2
  double angle_increment() const;  // radians between neighbouring beams; 0 for a single beam
  double angle(int beam) const { return angle_min() + beam * angle_increment(); }
};

// Throws Error unless beams >= 1, 0 < field of view <= 360 degrees and 0 <= min_range <
// max_range (all finite).
void CheckLaserModel(const LaserModel& laser);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SIM_LASER_MODEL_H_
