// Chunk sequences from a client: each frame is decoded as a client request, and each chunk in one
// goes into the upload's bookkeeping and its assembler. Any order, size, repetition or content is
// either taken or refused with a ProtocolError; a complete upload reads back exactly its bytes.
//
// Input: one byte of flags, then frames, each a 2-byte little-endian length and that many bytes.
// Flags choose whether the announced size and SHA-256 are those of the chunks' bytes in frame
// order (so that an in-order sequence completes) or others (so that it is refused at the end).
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "common/protocol/wire.h"
#include "common/util/error.h"
#include "common/util/sha256.h"
#include "common/util/temp_dir.h"
#include "coordinator/upload_assembler.h"
#include "coordinator/upload_table.h"

namespace {

std::vector<std::string_view> Frames(std::string_view data) {
  std::vector<std::string_view> frames;
  while (data.size() >= 2) {
    const std::size_t size = static_cast<unsigned char>(data[0]) |
                             static_cast<std::size_t>(static_cast<unsigned char>(data[1])) << 8;
    data.remove_prefix(2);
    frames.push_back(data.substr(0, size));
    data.remove_prefix(frames.back().size());
  }
  return frames;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  static const evoslam::TempDir dir("evoslam-fuzz-upload");
  const std::uint8_t flags = data[0];
  std::vector<evoslam::proto::ClientRequest> requests;
  for (const std::string_view frame :
       Frames(std::string_view(reinterpret_cast<const char*>(data) + 1, size - 1))) {
    try {
      requests.push_back(evoslam::DecodeClientRequest(std::as_bytes(std::span(frame))));
    } catch (const evoslam::ProtocolError&) {
      // Refusing is the expected outcome for most frames.
    }
  }
  std::string sent;
  for (const auto& r : requests) sent += r.chunk().content();
  const std::uint64_t announced = (flags & 1) ? sent.size() : flags >> 2;
  const std::string sha = evoslam::Sha256Hex((flags & 2) ? std::string_view(sent) : "other");
  const std::size_t max_chunk = 1 + (flags >> 3);

  evoslam::UploadTable table(4);
  const evoslam::UploadTable::Clock::time_point now;
  const std::string id = table.Begin("", "fuzz.clf", announced, now);
  table.Answered(id, now);
  evoslam::UploadAssembler upload(dir / "spool", id, "fuzz.clf", sha, announced, max_chunk);
  for (const auto& r : requests) {
    if (!r.has_chunk()) continue;
    try {
      table.Accept(r.chunk().upload_id().empty() ? id : r.chunk().upload_id(), "", now);
      if (upload.Append(r.chunk().offset(), r.chunk().content())) {
        std::string back(static_cast<std::size_t>(upload.size()), '\0');
        upload.ReadBack(back);
        if (evoslam::Sha256Hex(back) != sha) __builtin_trap();  // stored bytes that are not its
      }
      table.Answered(id, now);
    } catch (const evoslam::ProtocolError&) {
      // A refusal: the upload is spoiled, and the chunks after it are refused too.
    }
  }
  return 0;
}
