#include "cli/option_parsing.h"

#include <spdlog/spdlog.h>
#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string_view>
#include <system_error>
#include <type_traits>
#include <vector>

#include "common/util/error.h"
#include "common/util/nearest_name.h"

namespace evoslam::cli {
namespace {

// The comma-separated pieces of `text` ("" gives one empty piece).
std::vector<std::string_view> SplitCommas(std::string_view text) {
  std::vector<std::string_view> pieces;
  std::size_t begin = 0;
  while (true) {
    const std::size_t end = std::min(text.find(',', begin), text.size());
    pieces.push_back(text.substr(begin, end - begin));
    if (end == text.size()) return pieces;
    begin = end + 1;
  }
}

template <typename T>
std::optional<T> ParseNumber(std::string_view text) {
  T v{};
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || ptr != text.data() + text.size()) return std::nullopt;
  if constexpr (std::is_floating_point_v<T>) {
    if (!std::isfinite(v)) return std::nullopt;
  }
  return v;
}

// A check that the text is a finite number for which `ok` holds.
CLI::Validator NumberValidator(bool (*ok)(double), const std::string& what,
                               const std::string& name) {
  return CLI::Validator(
      [ok, what](const std::string& text) -> std::string {
        const auto v = ParseNumber<double>(text);
        return v && ok(*v) ? "" : "'" + text + "' is not " + what;
      },
      name);
}

// A deprecated spelling's description: this, then the option's name. WarnDeprecatedNames finds
// the spellings used by it.
constexpr std::string_view kDeprecatedPrefix = "deprecated: use ";

}  // namespace

Pose2 ParsePose(const std::string& text, const std::string& flag) {
  std::vector<double> values;
  for (const std::string_view piece : SplitCommas(text)) {
    const auto v = ParseNumber<double>(piece);
    if (!v) throw Error(flag + ": expected x,y,theta (three numbers), got '" + text + "'");
    values.push_back(*v);
  }
  if (values.size() != 3)
    throw Error(flag + ": expected x,y,theta (three numbers), got '" + text + "'");
  return Pose2(values[0], values[1], values[2]);
}

CLI::Validator PositiveNumber() {
  return NumberValidator([](double v) { return v > 0.0; }, "a positive number", "POSITIVE");
}

CLI::Validator NonNegativeNumber() {
  return NumberValidator([](double v) { return v >= 0.0; }, "a number >= 0", "NONNEGATIVE");
}

CLI::Validator OneOf(std::vector<std::string> names) {
  std::string listed, braced;
  for (const std::string& name : names) {
    listed += (listed.empty() ? "" : ", ") + name;
    braced += (braced.empty() ? "{" : ",") + name;
  }
  return CLI::Validator(
      [names = std::move(names), listed](std::string& value) -> std::string {
        if (std::ranges::find(names, value) != names.end()) return "";
        std::string message = "'" + value + "' is not one of " + listed;
        if (const auto nearest = NearestName(value, names)) {
          message += "; did you mean '" + *nearest + "'?";
        }
        return message;
      },
      braced + "}");
}

void CheckOutputFolder(const std::string& flag, const std::string& folder) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path target = fs::absolute(folder, ec);
  if (ec) throw CLI::ValidationError(flag, "cannot resolve '" + folder + "': " + ec.message());
  // The folder itself when it exists, else the nearest existing folder above it, which the run
  // would create it in.
  fs::path path = target;
  while (!fs::exists(path, ec) && path.has_relative_path()) path = path.parent_path();
  if (!fs::is_directory(path, ec)) {
    throw CLI::ValidationError(flag, "'" + path.string() + "' is not a folder");
  }
  if (::access(path.c_str(), W_OK | X_OK) != 0) {
    throw CLI::ValidationError(
        flag, "cannot write into '" + path.string() + "'" +
                  (path == target ? std::string() : " to create '" + folder + "' there"));
  }
}

CLI::Option* AddLogOption(CLI::App* cmd, const std::string& positional, std::string& log,
                          const std::string& help) {
  const std::string spelling = positional + " or --log";
  return cmd
      ->add_option_function<std::vector<std::string>>(
          positional + ",--log",
          [&log, spelling](const std::vector<std::string>& given) {
            for (const std::string& other : given) {
              if (other != given.front()) {
                throw CLI::ValidationError(spelling, "two different files, '" + given.front() +
                                                         "' and '" + other + "'; give one");
              }
            }
            log = given.front();
          },
          help + "; as the positional " + positional + " or --log")
      ->type_name("FILE")
      // One value each time it is given; both spellings' values reach the check above.
      ->expected(1)
      ->allow_extra_args(true)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
}

void AddDeprecatedName(CLI::App* cmd, const std::string& old_name, CLI::Option* option) {
  const std::string name = option->get_name();
  cmd->add_option_function<std::string>(
         old_name,
         [old_name, name, option](const std::string& value) {
           option->add_result(value);
           try {
             option->run_callback();
           } catch (const CLI::ParseError& e) {
             // The error names the flag as typed: the warning that names the new one comes only
             // after parsing.
             throw CLI::ValidationError(old_name + " (deprecated; use " + name + ")", e.what());
           }
         },
         std::string(kDeprecatedPrefix) + name)
      ->group("");
}

void WarnDeprecatedNames(const CLI::App& app) {
  for (const CLI::Option* option : app.get_options()) {
    const std::string& description = option->get_description();
    if (option->count() > 0 && description.starts_with(kDeprecatedPrefix)) {
      // get_name is empty for a hidden option: its long name is the spelling used.
      spdlog::warn("--{} is deprecated; use {}", option->get_lnames().front(),
                   description.substr(kDeprecatedPrefix.size()));
    }
  }
  for (const CLI::App* used : app.get_subcommands()) WarnDeprecatedNames(*used);
}

}  // namespace evoslam::cli
