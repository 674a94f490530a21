#include <spdlog/spdlog.h>

#include <cstdio>
#include <string>

#include "cli/commands.h"
#include "cli/option_parsing.h"
#include "common/eval/trajectory_errors.h"
#include "common/io/carmen_reader.h"
#include "common/io/relations.h"
#include "common/io/trajectory_io.h"
#include "common/transform/angle_units.h"
#include "common/util/error.h"

namespace evoslam::cli {
namespace {

bool LooksLikeLog(const std::filesystem::path& path) {
  const std::string name = path.filename().string();
  return name.find(".clf") != std::string::npos || name.find(".log") != std::string::npos;
}

// A trajectory file, or a CARMEN log whose scans' stated poses are the trajectory (so raw
// odometry can be evaluated directly).
std::vector<StampedPose> LoadTrajectory(const std::filesystem::path& path, bool truth) {
  if (!LooksLikeLog(path)) return ReadTrajectory(path);
  const Dataset dataset = ReadCarmen(path);
  std::vector<StampedPose> poses;
  for (const LaserScan& scan : dataset.scans) {
    if (truth && !scan.true_pose) {
      throw Error(path.string() + ": the log has no ground truth (TRUEPOS) for scan at t=" +
                  std::to_string(scan.timestamp));
    }
    poses.push_back({scan.timestamp, truth ? *scan.true_pose : scan.pose});
  }
  return poses;
}

}  // namespace

void AddEvalCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "eval", "Errors of a trajectory against relations (Kuemmerle et al.) or ground truth");
  struct Args {
    std::string trajectory, relations, truth;
  };
  auto args = std::make_shared<Args>();
  AddLogOption(cmd, "trajectory", args->trajectory,
               "trajectory.txt / .tum, or a CARMEN log whose scans' poses are evaluated")
      ->required();
  CLI::App* reference =
      cmd->add_option_group("reference", "What the trajectory is measured against");
  reference->add_option("--relations", args->relations, "relations file")->type_name("FILE");
  reference
      ->add_option("--truth", args->truth,
                   "ground truth: trajectory file, or a log with TRUEPOS lines")
      ->type_name("FILE");
  reference->require_option(1);
  cmd->callback([args] {
    const auto trajectory = LoadTrajectory(args->trajectory, false);
    std::vector<Relation> relations;
    if (!args->relations.empty()) {
      relations = ReadRelations(args->relations);
    } else {
      const auto truth_poses = LoadTrajectory(args->truth, true);
      const AbsoluteErrors a = ComputeAbsoluteErrors(trajectory, truth_poses);
      if (a.poses == 0) throw Error("no pose of the trajectory has ground truth at its timestamp");
      std::printf(
          "absolute: %zu poses, RMS x %.4f m, y %.4f m, heading %.3f deg, "
          "translation %.4f m (max %.4f m); aligned to the truth by a rigid motion, "
          "translation %.4f m; by a rigid motion and a scale of %.4f, %.4f m\n",
          a.poses, a.rms_x, a.rms_y, Degrees(a.rms_theta), a.rms_translation, a.max_translation,
          a.aligned_rms_translation, a.alignment_scale, a.scale_aligned_rms_translation);
      relations = RelationsFromTruth(truth_poses);
    }
    const RelationErrors e = ComputeRelationErrors(trajectory, relations);
    if (e.relations == 0) {
      throw Error("none of the " + std::to_string(relations.size()) +
                  " relations falls on the trajectory's timestamps");
    }
    std::printf("relative: %zu relations (%zu skipped)\n", e.relations, e.skipped);
    std::printf("  translation %.4f +- %.4f m   squared %.4f +- %.4f m^2\n", e.translation_mean,
                e.translation_std, e.translation_sq_mean, e.translation_sq_std);
    std::printf("  rotation    %.3f +- %.3f deg squared %.3f +- %.3f deg^2\n",
                Degrees(e.rotation_mean), Degrees(e.rotation_std),
                Degrees(Degrees(e.rotation_sq_mean)), Degrees(Degrees(e.rotation_sq_std)));
  });
}

}  // namespace evoslam::cli
