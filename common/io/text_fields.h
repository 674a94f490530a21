#ifndef EVOSLAM_COMMON_IO_TEXT_FIELDS_H_
#define EVOSLAM_COMMON_IO_TEXT_FIELDS_H_

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace evoslam {

// Splits a line into its whitespace-separated (space, tab, CR) fields. The views point into line.
// *fields is cleared first so that a caller can reuse its capacity from line to line.
void SplitFields(std::string_view line, std::vector<std::string_view>* fields);

// The part of line before its first '#': the comment rule of evoslam's own text formats (line
// maps, routes). YAML's rule differs ('#' only after whitespace, outside quotes).
std::string_view StripHashComment(std::string_view line);

// Parse the whole of text as a number, locale-independently; nullopt when text is not exactly
// one number (empty, trailing characters, out of range). A leading '+' is accepted. ParseDouble
// and ParseFloat accept "nan" and "inf": callers that need finite values must check.
std::optional<double> ParseDouble(std::string_view text);
std::optional<float> ParseFloat(std::string_view text);
std::optional<std::size_t> ParseCount(std::string_view text);

// The shortest decimal text that reads back as exactly `value` (locale-independent).
std::string FormatShortest(double value);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_IO_TEXT_FIELDS_H_
