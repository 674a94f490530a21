#ifndef EVOSLAM_COMMON_PROTOCOL_CURVE_KEYS_H_
#define EVOSLAM_COMMON_PROTOCOL_CURVE_KEYS_H_

#include <filesystem>
#include <set>
#include <string>
#include <vector>

namespace evoslam {

// A ZeroMQ CURVE key pair in Z85 text (40 characters each), as zmq_curve_keypair makes them.
// The coordinator accepts only the public keys it is given; the secret keys never leave their
// host.
struct CurveKeyPair {
  std::string public_key;
  std::string secret_key;
};

CurveKeyPair GenerateCurveKeyPair();
// The public key that belongs to a secret key; throws Error for text that is not a Z85 key.
std::string CurvePublicKey(const std::string& secret_key);

// Writes NAME.pub (the public key, readable by all) and NAME.key (the secret key, readable by
// the owner only) in `dir`. Refuses to overwrite either unless `overwrite`.
void WriteCurveKeyPair(const CurveKeyPair& keys, const std::filesystem::path& dir,
                       const std::string& name, bool overwrite);
// Reads one key file (a .pub or a .key): one Z85 key, optionally followed by a newline.
std::string ReadCurveKey(const std::filesystem::path& path);
// The public keys in a list of .pub files and folders (every *.pub file in a folder); throws
// Error naming the file when one is not a key, or when the list yields no key at all.
std::set<std::string> ReadPublicKeys(const std::vector<std::filesystem::path>& paths);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_PROTOCOL_CURVE_KEYS_H_
