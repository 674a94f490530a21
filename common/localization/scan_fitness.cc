#include "common/localization/scan_fitness.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "common/util/error.h"

namespace evoslam {

FitnessKind ParseFitnessKind(std::string_view name) {
  if (name == "f3") return FitnessKind::kF3;
  if (name == "f2") return FitnessKind::kF2;
  throw Error("unknown fitness '" + std::string(name) + "' (expected f3 or f2)");
}

std::string_view FitnessKindName(FitnessKind kind) {
  return kind == FitnessKind::kF3 ? "f3" : "f2";
}

double ShiftLayout::shift_angle(std::size_t k) const {
  const double centre = 0.5 * static_cast<double>(shifts - 1);
  return (static_cast<double>(k) - centre) * static_cast<double>(shift_stride) * ray_step;
}

ShiftLayout MakeShiftLayout(const LaserScan& scan, double heading_half_window,
                            double heading_step) {
  if (scan.size() < 2 || !(scan.angle_increment > 0.0)) {
    throw Error("scan matching needs a scan with at least two beams and a positive increment");
  }
  if (!(heading_step > 0.0)) throw Error("heading step must be positive");
  if (!(heading_half_window >= 0.0)) throw Error("heading window must not be negative");
  ShiftLayout layout;
  const double inc = scan.angle_increment;
  if (inc >= heading_step) {
    layout.beam_stride = static_cast<std::size_t>(std::max(1.0, std::round(inc / heading_step)));
    layout.ray_step = inc / static_cast<double>(layout.beam_stride);
    layout.shift_stride = 1;
  } else {
    layout.beam_stride = 1;
    layout.ray_step = inc;
    layout.shift_stride = static_cast<std::size_t>(std::max(1.0, std::round(heading_step / inc)));
  }
  const double step = layout.ray_step * static_cast<double>(layout.shift_stride);
  const auto half = static_cast<std::size_t>(std::round(heading_half_window / step));
  layout.shifts = 2 * half + 1;
  layout.rays =
      (scan.size() - 1) * layout.beam_stride + (layout.shifts - 1) * layout.shift_stride + 1;
  layout.first_offset = scan.angle_min - static_cast<double>(half) * step;
  return layout;
}

ObservedBeams PrepareObservation(const LaserScan& scan, float max_range) {
  ObservedBeams beams;
  for (std::size_t i = 0; i < scan.size(); ++i) {
    if (scan.is_return(i) && scan.ranges[i] < max_range) {
      beams.index.push_back(i);
      beams.range.push_back(scan.ranges[i]);
    }
  }
  return beams;
}

namespace {

// The scoring loops are the estimator's hot spot. They are compiled twice, for AVX2 and for the
// baseline, and the loader picks the clone the CPU supports; the per-lane arithmetic (no fused
// multiply-add, exact abs, compare and add) gives the same bits with either.
#define EVOSLAM_VECTOR_CLONES __attribute__((target_clones("avx2", "default")))

// Per-shift sums, accumulated beam by beam: the inner loop runs over contiguous shifts, which the
// compiler vectorises, and each shift's sum is added in beam order, so the result does not depend
// on the vector width. An uncapped F3 takes an infinite cap, which leaves every term's bits as
// they are.
EVOSLAM_VECTOR_CLONES void AccumulateF3(const ShiftLayout& layout, const ObservedBeams& observed,
                                        std::span<const float> rays, float max_range, float cap,
                                        std::span<float> sums) {
  const std::size_t shifts = layout.shifts;
  const std::size_t stride = layout.shift_stride;
  // The sums never alias the rays: saying so lets the shift loop vectorise.
  float* __restrict acc = sums.data();
  std::fill(acc, acc + shifts, 0.0f);
  for (std::size_t j = 0; j < observed.index.size(); ++j) {
    const float b = observed.range[j];
    const float* __restrict a = rays.data() + observed.index[j] * layout.beam_stride;
    if (stride == 1) {
      for (std::size_t k = 0; k < shifts; ++k) {
        const float d = std::min(std::fabs(a[k] - b), cap);
        acc[k] += a[k] < max_range ? d : 0.0f;
      }
    } else {
      for (std::size_t k = 0; k < shifts; ++k) {
        const float ak = a[k * stride];
        const float d = std::min(std::fabs(ak - b), cap);
        acc[k] += ak < max_range ? d : 0.0f;
      }
    }
  }
}

EVOSLAM_VECTOR_CLONES void AccumulateF2(const FitnessParams& params, const ShiftLayout& layout,
                                        const ObservedBeams& observed, std::span<const float> rays,
                                        float max_range, std::span<float> sums) {
  const std::size_t shifts = layout.shifts;
  const std::size_t stride = layout.shift_stride;
  float* __restrict acc = sums.data();
  std::fill(acc, acc + shifts, 0.0f);
  const auto base = static_cast<float>(params.f2_base);
  const auto slope = static_cast<float>(params.f2_slope);
  for (std::size_t j = 0; j < observed.index.size(); ++j) {
    const float b = observed.range[j];
    const float* __restrict a = rays.data() + observed.index[j] * layout.beam_stride;
    for (std::size_t k = 0; k < shifts; ++k) {
      const float ak = a[k * stride];
      const bool inside = std::fabs(ak - b) <= base + slope * (ak + b);
      acc[k] -= (ak < max_range && inside) ? 1.0f : 0.0f;
    }
  }
}

float F3Cap(const FitnessParams& params) {
  return params.f3_cap > 0.0 ? static_cast<float>(params.f3_cap)
                             : std::numeric_limits<float>::infinity();
}

}  // namespace

ShiftScore BestShift(const FitnessParams& params, const ShiftLayout& layout,
                     const ObservedBeams& observed, std::span<const float> rays, float max_range,
                     std::span<float> scratch) {
  if (params.kind == FitnessKind::kF3) {
    AccumulateF3(layout, observed, rays, max_range, F3Cap(params), scratch);
  } else {
    AccumulateF2(params, layout, observed, rays, max_range, scratch);
  }
  // Scan outward from the centre so that ties keep the heading closest to the prediction.
  const std::size_t centre = layout.shifts / 2;
  ShiftScore best{scratch[centre], centre};
  for (std::size_t d = 1; d <= centre; ++d) {
    for (std::size_t k : {centre - d, centre + d}) {
      if (scratch[k] < best.fitness) best = {scratch[k], k};
    }
  }
  return best;
}

double ScoreAligned(const FitnessParams& params, const ObservedBeams& observed,
                    std::span<const float> rays, float max_range) {
  float sum = 0.0f;
  const float cap = F3Cap(params);
  for (std::size_t j = 0; j < observed.index.size(); ++j) {
    const float a = rays[observed.index[j]];
    const float b = observed.range[j];
    if (!(a < max_range)) continue;
    if (params.kind == FitnessKind::kF3) {
      sum += std::min(std::fabs(a - b), cap);
    } else if (std::fabs(a - b) <= static_cast<float>(params.f2_base + params.f2_slope * (a + b))) {
      sum -= 1.0f;
    }
  }
  return sum;
}

}  // namespace evoslam
