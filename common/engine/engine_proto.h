#ifndef EVOSLAM_COMMON_ENGINE_ENGINE_PROTO_H_
#define EVOSLAM_COMMON_ENGINE_ENGINE_PROTO_H_

#include <cstdint>

#include "common/engine/archipelago.h"
#include "common/engine/island.h"
#include "evoslam/engine.pb.h"

namespace evoslam {

// The version written into, and required of, every engine checkpoint.
inline constexpr std::uint32_t kEngineProtocolVersion = 1;

// Conversions between the engine's value types and their wire form. The FromProto functions
// check everything a corrupt or hostile message could get wrong (versions, shapes, names,
// parameter ranges) and throw Error saying what; they never crash on bad input.
proto::Matrix ToProto(const Eigen::MatrixXd& m);
Eigen::MatrixXd FromProto(const proto::Matrix& m, const char* what);

proto::AlgorithmSettings ToProto(const AlgorithmSpec& spec);
AlgorithmSpec FromProto(const proto::AlgorithmSettings& settings);

proto::StopSettings ToProto(const StopCriteria& stop);
StopCriteria FromProto(const proto::StopSettings& stop);

proto::MigrationSettings ToProto(const MigrationParams& migration);
MigrationParams FromProto(const proto::MigrationSettings& migration);

proto::IslandModelSettings ToProto(const IslandModelParams& params);
IslandModelParams FromProto(const proto::IslandModelSettings& params);

proto::IslandCheckpoint ToProto(const IslandCheckpoint& checkpoint);
IslandCheckpoint FromProto(const proto::IslandCheckpoint& checkpoint);

proto::ArchipelagoCheckpoint ToProto(const ArchipelagoCheckpoint& checkpoint);
ArchipelagoCheckpoint FromProto(const proto::ArchipelagoCheckpoint& checkpoint);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_ENGINE_ENGINE_PROTO_H_
