#include "common/io/text_fields.h"

#include <charconv>
#include <system_error>

namespace evoslam {
namespace {

bool IsSpace(char c) { return c == ' ' || c == '\t' || c == '\r'; }

// from_chars rejects the '+' that other writers (printf "%+f") may emit.
std::string_view WithoutPlus(std::string_view text) {
  if (text.size() > 1 && text.front() == '+' && text[1] != '-' && text[1] != '+') {
    text.remove_prefix(1);
  }
  return text;
}

template <typename T>
std::optional<T> ParseWhole(std::string_view text) {
  text = WithoutPlus(text);
  T value{};
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ec != std::errc() || ptr != end || text.empty()) return std::nullopt;
  return value;
}

}  // namespace

void SplitFields(std::string_view line, std::vector<std::string_view>* fields) {
  fields->clear();
  std::size_t i = 0;
  const std::size_t n = line.size();
  while (i < n) {
    while (i < n && IsSpace(line[i])) ++i;
    const std::size_t start = i;
    while (i < n && !IsSpace(line[i])) ++i;
    if (i > start) fields->push_back(line.substr(start, i - start));
  }
}

std::string_view StripHashComment(std::string_view line) {
  const std::size_t hash = line.find('#');
  return hash == std::string_view::npos ? line : line.substr(0, hash);
}

std::optional<double> ParseDouble(std::string_view text) { return ParseWhole<double>(text); }

std::optional<float> ParseFloat(std::string_view text) { return ParseWhole<float>(text); }

std::optional<std::size_t> ParseCount(std::string_view text) {
  return ParseWhole<std::size_t>(text);
}

std::string FormatShortest(double value) {
  // 32 characters hold any double's shortest form ("-2.2250738585072014e-308" is 24).
  char buffer[32];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, end);
}

}  // namespace evoslam
