#ifndef EVOSLAM_COMMON_UTIL_RANDOM_ID_H_
#define EVOSLAM_COMMON_UTIL_RANDOM_ID_H_

#include <cstddef>
#include <string>

namespace evoslam {

// `bytes` bytes from the system's CSPRNG (libsodium's randombytes_buf) as 2 * `bytes` lowercase
// hex digits: an id nobody can guess and no other draw repeats (16 bytes, 128 bits, make a
// collision as likely as never). Not the engine's Rng, whose streams are seeded to repeat.
std::string RandomHexId(std::size_t bytes);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_UTIL_RANDOM_ID_H_
