// Bytes from a coordinator: decoding either yields an envelope or refuses with a ProtocolError.
#include <cstddef>
#include <cstdint>
#include <span>

#include "common/protocol/wire.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    evoslam::DecodeCoordinatorMessage(std::as_bytes(std::span(data, size)));
  } catch (const evoslam::ProtocolError&) {
    // Refusing is the expected outcome for almost every input.
  }
  return 0;
}
