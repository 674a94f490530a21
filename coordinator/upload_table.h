#ifndef EVOSLAM_COORDINATOR_UPLOAD_TABLE_H_
#define EVOSLAM_COORDINATOR_UPLOAD_TABLE_H_

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace evoslam {

// The most bytes one chunk of an upload holds. Big enough that a chunk's round trip costs little
// next to its bytes; the coordinator holds at most kUploadWindow of them per upload.
inline constexpr std::size_t kUploadChunkBytes = std::size_t{4} << 20;
// Chunks a client may send ahead of their answers, so that the next chunk travels while the last
// is written.
inline constexpr std::uint32_t kUploadWindow = 2;

// Refuses (ProtocolError QUOTA_EXCEEDED) a dataset of `size` bytes when the client's `stored`
// bytes (and those of its uploads under way) would go over its `quota` with it; 0: no quota.
void CheckQuota(const std::string& name, std::uint64_t size, std::uint64_t stored,
                std::uint64_t quota);

// The uploads under way, as the broker sees them: whose each is, the bytes it will take, how many
// of its requests wait for the intake, and when its client was last heard from. Broker thread
// only.
class UploadTable {
 public:
  using Clock = std::chrono::steady_clock;

  explicit UploadTable(std::size_t max_uploads) : max_uploads_(max_uploads) {}

  // A new upload of `owner`, under a random id, its first request (the start) waiting. Throws
  // ProtocolError QUEUE_FULL when `max_uploads` are under way.
  std::string Begin(const std::string& owner, const std::string& name, std::uint64_t size,
                    Clock::time_point now);
  // Takes a chunk of upload `id` from `owner`. Throws ProtocolError: UNKNOWN_UPLOAD when `owner`
  // has no such upload under way (another's counts as none), QUEUE_FULL when `kUploadWindow`
  // chunks of it wait already; the latter ends the upload.
  void Accept(const std::string& id, const std::string& owner, Clock::time_point now);
  // A request of the upload was answered; it goes on.
  void Answered(const std::string& id, Clock::time_point now);
  void End(const std::string& id);

  // Bytes `owner`'s uploads under way will take once stored.
  std::uint64_t Reserved(const std::string& owner) const;
  // The uploads not heard from since `before` with nothing waiting: their clients are gone. They
  // stay until ended.
  std::vector<std::string> Silent(Clock::time_point before) const;
  std::string NameOf(const std::string& id) const;
  std::size_t size() const { return uploads_.size(); }

 private:
  struct Upload {
    std::string owner;
    std::string name;
    std::uint64_t size = 0;
    std::uint32_t waiting = 0;  // requests handed to the intake, not answered yet
    Clock::time_point heard;
  };
  std::size_t max_uploads_;
  std::map<std::string, Upload> uploads_;
};

}  // namespace evoslam

#endif  // EVOSLAM_COORDINATOR_UPLOAD_TABLE_H_
