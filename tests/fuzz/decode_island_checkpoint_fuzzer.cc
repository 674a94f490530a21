// An island checkpoint as a worker or the database hands it back: parsing and validating it
// either yields an island that can continue, or refuses with an Error.
#include <cstddef>
#include <cstdint>

#include "common/engine/engine_proto.h"
#include "common/util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  evoslam::proto::IslandCheckpoint message;
  if (!message.ParseFromArray(data, static_cast<int>(size))) return 0;
  try {
    const evoslam::IslandCheckpoint checkpoint = evoslam::FromProto(message);
    evoslam::Island::FromCheckpoint(checkpoint);
  } catch (const evoslam::Error&) {
    // A checkpoint that does not fit its parameters is refused, which is what is tested.
  }
  return 0;
}
