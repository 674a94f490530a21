#ifndef EVOSLAM_COMMON_IO_CARMEN_FORMAT_H_
#define EVOSLAM_COMMON_IO_CARMEN_FORMAT_H_

#include <cstddef>
#include <numbers>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace evoslam {

// Conventions of CARMEN logs shared by the reader and the writer, so that what one writes the
// other reads back the same.

// FLASER/RLASER lines carry only a beam count: the beams span 180 degrees from -90 degrees.
inline constexpr double kFlaserAngleMin = -std::numbers::pi / 2.0;

// Beam spacing of an n-beam FLASER/RLASER scan. An odd count includes both ends of the
// half-circle (181 -> 1 deg, 361 -> 0.5 deg); an even one leaves out the last (180 -> 1 deg).
// Fewer than two beams span nothing: 0.
double FlaserAngleIncrement(std::size_t beams);

// range_max of FLASER/RLASER scans when the log gives no PARAM for it. The SICK logs mark "no
// return" at or above 50 m: ACES with 50.00, Intel with 81.83, MIT CSAIL with 81.91, while their
// largest real readings are below 50 m (ACES 49.9, Intel 26.4, MIT 42.4). With 50 such markers
// fail range_min < r < range_max and so are not returns.
inline constexpr double kCarmenDefaultRangeMax = 50.0;

// Whether a PARAM names the maximum range of the front (or, with rear, the rear) laser.
bool IsRangeMaxParam(std::string_view name, bool rear);

// The value of a maximum-range PARAM: a positive finite number, else nullopt.
std::optional<double> ParseRangeMaxParam(std::string_view value);

// range_max of the FLASER (front) or RLASER (rear) scans of a log with these params: the last
// valid maximum-range PARAM for that laser; for the rear laser without one, the front laser's;
// otherwise kCarmenDefaultRangeMax.
double CarmenRangeMax(const std::vector<std::pair<std::string, std::string>>& params, bool rear);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_IO_CARMEN_FORMAT_H_
