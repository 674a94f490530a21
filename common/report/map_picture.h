#ifndef EVOSLAM_COMMON_REPORT_MAP_PICTURE_H_
#define EVOSLAM_COMMON_REPORT_MAP_PICTURE_H_

#include <Eigen/Core>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "common/image/image.h"
#include "common/io/trajectory_io.h"
#include "common/localization/map_model.h"
#include "common/transform/pose2.h"

namespace evoslam {

// The pictures' colours, the same in every job's pictures.
inline constexpr Rgb kEstimateColor{220, 30, 30};
inline constexpr Rgb kTruthColor{0, 160, 0};
inline constexpr Rgb kComparedColor{150, 60, 200};
// Odometry is faded: it tells least, and drifts far from everything else.
inline constexpr Rgb kOdometryColor{150, 175, 240};
inline constexpr Rgb kLoopColor{240, 140, 0};
// Words, the scale bar and the outlines of the legend's swatches.
inline constexpr Rgb kInkColor{40, 40, 40};

// The map area's longer side, pixels: at least 1,000 whatever the map's size or cell size.
inline constexpr int kMapAreaPixels = 1200;

// What a trajectory is, which sets how it is drawn. Layers are drawn in this order, each over
// the ones before: the truth as a broad band, so that it shows on both sides of an estimate that
// follows it, and the estimate as a thin line on top.
enum class LayerKind { kOdometry, kTruth, kCompared, kEstimate };

struct TrajectoryLayer {
  LayerKind kind;
  std::string label;  // the legend's words for it
  std::vector<Pose2> poses;
};

// A trajectory's poses as a layer; the timestamps play no part in a picture.
TrajectoryLayer MakeLayer(LayerKind kind, std::string label,
                          std::span<const StampedPose> trajectory);

// A loop closure: the two places it joins.
struct LoopLink {
  Eigen::Vector2d earlier;
  Eigen::Vector2d later;
};

struct MapPictureContent {
  std::string title;
  std::vector<TrajectoryLayer> layers;
  // A SLAM run's trajectory picture: the loops closed are drawn, and counted in the legend even
  // when there are none.
  bool shows_loops = false;
  std::vector<LoopLink> loops;
};

// The title over the map area; under it a legend (each layer, the loops, what the map's colours
// mean) and a scale bar in metres. The map area is kMapAreaPixels on its longer side and frames
// the map (a grid's occupied cells bar a few strays, or the walls) and every layer but odometry,
// which is clipped at the frame rather than squeezing the map into a corner.
Image DrawMapPicture(const MapModel& map, const MapPictureContent& content);

// DrawMapPicture written as PNG; throws Error naming the path on failure.
void WriteMapPicture(const MapModel& map, const MapPictureContent& content,
                     const std::filesystem::path& path);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_REPORT_MAP_PICTURE_H_
