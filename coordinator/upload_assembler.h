#ifndef EVOSLAM_COORDINATOR_UPLOAD_ASSEMBLER_H_
#define EVOSLAM_COORDINATOR_UPLOAD_ASSEMBLER_H_

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <string_view>

#include "common/util/sha256.h"
#include "evoslam/service.pb.h"

namespace evoslam {

// Refuses (ProtocolError TOO_LARGE) a chunk of `bytes` over `max_chunk_bytes`.
void CheckChunkSize(std::size_t bytes, std::size_t max_chunk_bytes, const std::string& upload_id);

// One dataset arriving in chunks: each chunk written in order to a spool file and hashed as it
// comes, so that no more of an upload than one chunk is ever in memory. The spool file goes with
// the object. Any refusal spoils it: the upload is then dropped.
class UploadAssembler {
 public:
  // Creates (or empties) the spool file; throws Error naming it when it cannot.
  UploadAssembler(std::filesystem::path spool, std::string upload_id, std::string name,
                  std::string sha256, std::uint64_t size, std::size_t max_chunk_bytes);
  ~UploadAssembler();
  UploadAssembler(const UploadAssembler&) = delete;
  UploadAssembler& operator=(const UploadAssembler&) = delete;

  // Appends the chunk that starts at `offset`; returns whether the dataset is complete, its bytes
  // hashing to the announced SHA-256. Throws ProtocolError: INVALID for a chunk that does not
  // start where the bytes so far end, an empty chunk of a dataset that is not empty, a chunk past
  // the announced size, bytes that hash to another SHA-256, or any chunk after a refusal or after
  // the last; TOO_LARGE for a chunk over the limit. Throws Error when the spool cannot be written.
  bool Append(std::uint64_t offset, std::string_view bytes);

  // Once complete: fills `piece` with the next bytes of the dataset, read back from the spool
  // from its start. Throws Error when the spool cannot be read.
  void ReadBack(std::span<char> piece);

  const std::string& upload_id() const { return upload_id_; }
  const std::string& name() const { return name_; }
  const std::string& sha256() const { return sha256_; }
  std::uint64_t size() const { return size_; }
  std::uint64_t received() const { return received_; }
  bool complete() const { return complete_; }

 private:
  struct Close {
    void operator()(std::FILE* file) const { std::fclose(file); }
  };
  // Throws the refusal, spoiling the upload.
  [[noreturn]] void Refuse(proto::ErrorCode code, const std::string& why);

  std::filesystem::path spool_;
  std::string upload_id_, name_, sha256_;
  std::uint64_t size_;
  std::size_t max_chunk_bytes_;
  std::unique_ptr<std::FILE, Close> file_;
  Sha256 hasher_;
  std::uint64_t received_ = 0;
  bool complete_ = false;
  bool spoiled_ = false;
};

}  // namespace evoslam

#endif  // EVOSLAM_COORDINATOR_UPLOAD_ASSEMBLER_H_
