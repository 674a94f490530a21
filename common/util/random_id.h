#ifndef EVOSLAM_COMMON_UTIL_RANDOM_ID_H_
#define EVOSLAM_COMMON_UTIL_RANDOM_ID_H_

#include <string>
#include <string_view>

namespace evoslam {

// `prefix` and 32 lowercase hex digits: 128 bits from the system's CSPRNG (libsodium), so that
// knowing one id tells nothing of another and nobody can guess one.
std::string RandomId(std::string_view prefix);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_UTIL_RANDOM_ID_H_
