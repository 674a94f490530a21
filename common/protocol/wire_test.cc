#include "common/protocol/wire.h"

#include <google/protobuf/stubs/logging.h>
#include <google/protobuf/unknown_field_set.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "common/util/random.h"

namespace evoslam {
namespace {

std::span<const std::byte> Bytes(const std::string& s) {
  return std::as_bytes(std::span(s.data(), s.size()));
}

proto::ClientRequest Submit() {
  proto::ClientRequest r;
  r.set_request_id(7);
  auto* spec = r.mutable_submit()->mutable_spec();
  spec->set_kind(proto::JOB_KIND_LOCALIZE);
  spec->mutable_log()->set_sha256(std::string(64, 'a'));
  spec->set_seed(3);
  spec->mutable_localize()->set_optimizer("de");
  return r;
}

template <typename Decode>
proto::ErrorCode RefusalCode(Decode decode, const std::string& frame) {
  try {
    decode(Bytes(frame));
  } catch (const ProtocolError& e) {
    return e.code();
  }
  return proto::ERROR_CODE_UNSPECIFIED;
}

const auto kDecodeRequest = [](std::span<const std::byte> f) { return DecodeClientRequest(f); };
const auto kDecodeWorker = [](std::span<const std::byte> f) { return DecodeWorkerMessage(f); };

TEST(WireTest, EncodeStampsTheVersionAndDecodeRoundTrips) {
  const proto::ClientRequest back = DecodeClientRequest(Bytes(Encode(Submit())));
  EXPECT_EQ(back.protocol_version(), kProtocolVersion);
  EXPECT_EQ(back.request_id(), 7u);
  EXPECT_EQ(back.submit().spec().seed(), 3u);
  EXPECT_EQ(back.submit().spec().localize().optimizer(), "de");

  proto::WorkerMessage ready;
  ready.mutable_ready()->set_threads(2);
  EXPECT_EQ(DecodeWorkerMessage(Bytes(Encode(ready))).ready().threads(), 2u);
  proto::CoordinatorMessage task;
  task.mutable_task()->set_task_id("t1");
  EXPECT_EQ(DecodeCoordinatorMessage(Bytes(Encode(task))).task().task_id(), "t1");
  const proto::ClientReply error = ErrorReplyFor(9, proto::ERROR_CODE_QUEUE_FULL, "full");
  EXPECT_EQ(DecodeClientReply(Bytes(error.SerializeAsString())).error().code(),
            proto::ERROR_CODE_QUEUE_FULL);
}

TEST(WireTest, AnotherVersionIsRefusedSayingWhichVersions) {
  proto::ClientRequest r = Submit();
  r.set_protocol_version(kProtocolVersion + 1);
  try {
    DecodeClientRequest(Bytes(r.SerializeAsString()));
    FAIL() << "accepted version " << r.protocol_version();
  } catch (const ProtocolError& e) {
    EXPECT_EQ(e.code(), proto::ERROR_CODE_BAD_VERSION);
    const std::string what = e.what();
    EXPECT_NE(what.find("version " + std::to_string(kProtocolVersion + 1)), std::string::npos)
        << what;
    EXPECT_NE(what.find("speaks " + std::to_string(kProtocolVersion)), std::string::npos) << what;
  }
  // A frame without any version (an old or foreign peer) is version 0.
  proto::WorkerMessage unversioned;
  unversioned.mutable_heartbeat();
  EXPECT_EQ(RefusalCode(kDecodeWorker, unversioned.SerializeAsString()),
            proto::ERROR_CODE_BAD_VERSION);
}

// A client of version 2 sent a dataset whole, its bytes in UploadDataset's field 2: the frame is
// refused by its version, with a message a person can act on, not read as an upload of nothing.
TEST(WireTest, AVersion2WholeUploadIsRefusedNamingBothVersions) {
  proto::ClientRequest old;
  old.set_protocol_version(2);
  old.set_request_id(5);
  old.mutable_upload()->set_name("log.clf");
  old.mutable_upload()->set_sha256(std::string(64, 'a'));
  old.mutable_upload()
      ->GetReflection()
      ->MutableUnknownFields(old.mutable_upload())
      ->AddLengthDelimited(2, "the whole log");
  try {
    DecodeClientRequest(Bytes(old.SerializeAsString()));
    FAIL() << "accepted";
  } catch (const ProtocolError& e) {
    EXPECT_EQ(e.code(), proto::ERROR_CODE_BAD_VERSION);
    EXPECT_NE(std::string(e.what()).find("speaks protocol version 2, this build speaks " +
                                         std::to_string(kProtocolVersion)),
              std::string::npos)
        << e.what();
  }
}

TEST(WireTest, UploadChunksRoundTrip) {
  proto::ClientRequest r;
  r.mutable_chunk()->set_upload_id("upload-1");
  r.mutable_chunk()->set_offset(4194304);
  r.mutable_chunk()->set_content(std::string("\0\xff chunk", 8));
  const proto::ClientRequest back = DecodeClientRequest(Bytes(Encode(r)));
  EXPECT_EQ(back.chunk().upload_id(), "upload-1");
  EXPECT_EQ(back.chunk().offset(), 4194304u);
  EXPECT_EQ(back.chunk().content(), std::string("\0\xff chunk", 8));
  proto::ClientRequest start;
  start.mutable_upload()->set_sha256(std::string(64, 'a'));
  EXPECT_FALSE(DecodeClientRequest(Bytes(Encode(start))).upload().has_size_bytes());
  start.mutable_upload()->set_size_bytes(0);
  EXPECT_TRUE(DecodeClientRequest(Bytes(Encode(start))).upload().has_size_bytes());
}

TEST(WireTest, TruncatedEmptyAndOversizedFramesAreRefused) {
  const std::string frame = Encode(Submit());
  EXPECT_EQ(RefusalCode(kDecodeRequest, frame.substr(0, frame.size() - 3)),
            proto::ERROR_CODE_MALFORMED);
  // An empty frame parses as an empty envelope: version 0.
  EXPECT_EQ(RefusalCode(kDecodeRequest, ""), proto::ERROR_CODE_BAD_VERSION);
  proto::ClientRequest no_request;
  EXPECT_EQ(RefusalCode(kDecodeRequest, Encode(no_request)), proto::ERROR_CODE_MALFORMED);
  WireLimits small;
  small.max_frame_bytes = 16;
  try {
    DecodeClientRequest(Bytes(frame), small);
    FAIL();
  } catch (const ProtocolError& e) {
    EXPECT_EQ(e.code(), proto::ERROR_CODE_TOO_LARGE);
  }
}

// Counts the frames a decoder accepts; every refusal must be a ProtocolError with a code (any
// other exception, or a crash, fails the test).
template <typename Decode>
int Accepted(Decode decode, const std::vector<std::string>& frames) {
  int accepted = 0;
  for (const std::string& frame : frames) {
    try {
      decode(Bytes(frame));
      ++accepted;
    } catch (const ProtocolError& e) {
      EXPECT_NE(e.code(), proto::ERROR_CODE_UNSPECIFIED);
    }
  }
  return accepted;
}

TEST(WireTest, RandomBytesAreRefusedNeverCrash) {
  const google::protobuf::LogSilencer quiet;
  Rng rng(5);
  const std::string valid = Encode(Submit());
  std::vector<std::string> flipped, random;
  for (int trial = 0; trial < 2500; ++trial) {
    std::string frame = valid;
    for (int k = 0; k < 3; ++k)
      frame[rng.UniformIndex(frame.size())] = static_cast<char>(rng.NextU64());
    flipped.push_back(frame);
    frame.resize(rng.UniformIndex(300));
    for (char& c : frame) c = static_cast<char>(rng.NextU64());
    random.push_back(frame);
  }
  // Flipping bytes of a valid frame sometimes leaves a valid one; random bytes almost never are.
  EXPECT_LT(Accepted(kDecodeRequest, flipped), 2000);
  EXPECT_LT(Accepted(kDecodeRequest, random), 50);
  EXPECT_LT(Accepted(kDecodeWorker, random), 50);
  const auto decode_coordinator = [](std::span<const std::byte> f) {
    return DecodeCoordinatorMessage(f);
  };
  EXPECT_LT(Accepted(decode_coordinator, random), 50);
}

}  // namespace
}  // namespace evoslam
