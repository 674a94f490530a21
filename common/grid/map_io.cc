#include "common/grid/map_io.h"

#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "common/image/image.h"
#include "common/image/pgm.h"
#include "common/io/text_fields.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

namespace fs = std::filesystem;

// Pixel values WriteMapYaml uses, and the thresholds that read them back.
constexpr std::uint8_t kOccupiedValue = 0;
constexpr std::uint8_t kFreeValue = 254;
constexpr std::uint8_t kUnknownValue = 205;
constexpr double kWrittenOccupiedThresh = 0.65;
constexpr double kWrittenFreeThresh = 0.196;

std::string_view Trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

// Drops a YAML comment: '#' at the start or after whitespace, outside quotes.
std::string_view StripComment(std::string_view line) {
  char quote = 0;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quote != 0) {
      if (c == quote) quote = 0;
    } else if (c == '"' || c == '\'') {
      quote = c;
    } else if (c == '#' && (i == 0 || std::isspace(static_cast<unsigned char>(line[i - 1])))) {
      return line.substr(0, i);
    }
  }
  return line;
}

struct Entry {
  std::string value;
  std::size_t line = 0;
};

class YamlMap {
 public:
  explicit YamlMap(const fs::path& path) : source_(path.string()) {
    std::ifstream in(path);
    if (!in) throw InputError(source_, 0, "cannot open map YAML file");
    Parse(in);
  }
  YamlMap(std::istream& in, std::string source) : source_(std::move(source)) { Parse(in); }

  const std::string& source() const { return source_; }

  const Entry* Find(const std::string& key) const {
    const auto it = entries_.find(key);
    return it == entries_.end() ? nullptr : &it->second;
  }

  const Entry& Require(const std::string& key, const std::string& expected) const {
    const Entry* entry = Find(key);
    if (entry == nullptr) {
      throw InputError(source_, 0, "missing key '" + key + "' (expected " + expected + ")");
    }
    if (entry->value.empty()) {
      throw InputError(source_, entry->line,
                       "key '" + key + "' has no value; expected " + expected);
    }
    return *entry;
  }

  // A scalar without its surrounding quotes, if it has any.
  static std::string Unquote(const std::string& value) {
    if (value.size() >= 2 && (value.front() == '"' || value.front() == '\'') &&
        value.back() == value.front()) {
      return value.substr(1, value.size() - 2);
    }
    return value;
  }

  double Number(std::string_view text, std::size_t line, const std::string& what) const {
    std::string_view s = Trim(text);
    if (!s.empty() && s.front() == '+') s.remove_prefix(1);
    double value = 0.0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
    if (s.empty() || ec != std::errc() || end != s.data() + s.size() || !std::isfinite(value)) {
      throw InputError(source_, line,
                       "expected " + what + " (a number), got '" + std::string(Trim(text)) + "'");
    }
    return value;
  }

  double Number(const std::string& key, const std::string& what) const {
    const Entry& entry = Require(key, what);
    return Number(Unquote(entry.value), entry.line, what);
  }

 private:
  void Parse(std::istream& in) {
    std::string raw;
    std::size_t number = 0;
    while (std::getline(in, raw)) {
      ++number;
      if (!raw.empty() && (raw.front() == ' ' || raw.front() == '\t') &&
          !Trim(StripComment(raw)).empty()) {
        throw InputError(source_, number,
                         "expected 'key: value' at the start of the line; nested YAML is not "
                         "supported");
      }
      const std::string_view line = Trim(StripComment(raw));
      if (line.empty() || line == "---" || line == "...") continue;
      const std::size_t colon = line.find(':');
      if (colon == std::string_view::npos || colon == 0) {
        throw InputError(source_, number, "expected 'key: value', got '" + std::string(line) + "'");
      }
      const std::string key(Trim(line.substr(0, colon)));
      const auto [it, inserted] =
          entries_.emplace(key, Entry{std::string(Trim(line.substr(colon + 1))), number});
      if (!inserted) {
        throw InputError(
            source_, number,
            "duplicate key '" + key + "' (first on line " + std::to_string(it->second.line) + ")");
      }
    }
    if (in.bad()) throw InputError(source_, 0, "cannot read map YAML file");
  }

  std::string source_;
  std::map<std::string, Entry> entries_;
};

struct MapSpec {
  fs::path image;
  std::size_t image_line = 0;
  double resolution = 0.0;
  Eigen::Vector2d origin{0.0, 0.0};
  bool negate = false;
  double occupied_thresh = 0.0;
  double free_thresh = 0.0;
};

MapSpec ParseSpec(const YamlMap& yaml, const fs::path& yaml_path) {
  MapSpec spec;
  const Entry& image = yaml.Require("image", "the map image's file name");
  spec.image = YamlMap::Unquote(image.value);
  if (spec.image.is_relative()) spec.image = yaml_path.parent_path() / spec.image;
  spec.image_line = image.line;

  spec.resolution = yaml.Number("resolution", "metres per pixel");
  if (spec.resolution <= 0.0) {
    throw InputError(yaml.source(), yaml.Find("resolution")->line, "resolution must be positive");
  }

  const Entry& origin = yaml.Require("origin", "[x, y, yaw]");
  const std::string_view list = Trim(origin.value);
  if (list.size() < 2 || list.front() != '[' || list.back() != ']') {
    throw InputError(yaml.source(), origin.line,
                     "expected origin as [x, y, yaw], got '" + origin.value + "'");
  }
  std::vector<double> values;
  std::string_view rest = list.substr(1, list.size() - 2);
  while (true) {
    const std::size_t comma = rest.find(',');
    values.push_back(yaml.Number(rest.substr(0, comma), origin.line, "an origin coordinate"));
    if (comma == std::string_view::npos) break;
    rest.remove_prefix(comma + 1);
  }
  if (values.size() != 3) {
    throw InputError(
        yaml.source(), origin.line,
        "expected origin as [x, y, yaw] (3 numbers), got " + std::to_string(values.size()));
  }
  if (values[2] != 0.0) {
    throw InputError(yaml.source(), origin.line,
                     "origin yaw " + std::to_string(values[2]) +
                         " is not supported; expected 0 (an unrotated map)");
  }
  spec.origin = {values[0], values[1]};

  const Entry& negate = yaml.Require("negate", "0 or 1");
  const std::string n = YamlMap::Unquote(negate.value);
  if (n == "0" || n == "false") {
    spec.negate = false;
  } else if (n == "1" || n == "true") {
    spec.negate = true;
  } else {
    throw InputError(yaml.source(), negate.line, "expected negate 0 or 1, got '" + n + "'");
  }

  spec.occupied_thresh = yaml.Number("occupied_thresh", "a probability");
  spec.free_thresh = yaml.Number("free_thresh", "a probability");
  const std::size_t occupied_line = yaml.Find("occupied_thresh")->line;
  if (spec.occupied_thresh < 0.0 || spec.occupied_thresh > 1.0) {
    throw InputError(yaml.source(), occupied_line, "occupied_thresh must lie in [0, 1]");
  }
  if (spec.free_thresh < 0.0 || spec.free_thresh > spec.occupied_thresh) {
    throw InputError(yaml.source(), yaml.Find("free_thresh")->line,
                     "free_thresh must lie in [0, occupied_thresh]");
  }

  if (const Entry* mode = yaml.Find("mode"); mode != nullptr) {
    const std::string m = YamlMap::Unquote(mode->value);
    if (m != "trinary" && m != "scale") {
      throw InputError(yaml.source(), mode->line,
                       "mode '" + m + "' is not supported; expected trinary or scale");
    }
  }
  return spec;
}

// The map image as gray values with their maxval, from a PGM or (averaging the channels) a PNG.
GrayImage ReadMapImage(const MapSpec& spec, const std::string& yaml_source) {
  std::ifstream in(spec.image, std::ios::binary);
  if (!in) {
    throw InputError(yaml_source, spec.image_line,
                     "cannot open map image '" + spec.image.string() + "'");
  }
  std::array<char, 8> magic{};
  in.read(magic.data(), magic.size());
  const std::string_view head(magic.data(), static_cast<std::size_t>(in.gcount()));
  in.close();
  // The grid's cell limit is checked on the image's header, before decoding a picture too large
  // to become a map.
  constexpr auto kMaxPixels = static_cast<std::uint64_t>(OccupancyGrid::kMaxCells);
  if (head.starts_with("P5") || head.starts_with("P2")) return ReadPgm(spec.image, kMaxPixels);
  if (head.starts_with("\x89PNG")) {
    const Image rgb = ReadPng(spec.image, kMaxPixels);
    GrayImage gray;
    gray.width = rgb.width();
    gray.height = rgb.height();
    gray.pixels.reserve(static_cast<std::size_t>(gray.width) * gray.height);
    for (int y = 0; y < rgb.height(); ++y) {
      for (int x = 0; x < rgb.width(); ++x) {
        const Rgb& p = rgb.at(x, y);
        gray.pixels.push_back(static_cast<std::uint8_t>((p.r + p.g + p.b) / 3));
      }
    }
    return gray;
  }
  throw InputError(spec.image.string(), 0, "unsupported map image; expected a PGM or PNG file");
}

}  // namespace

OccupancyGrid ReadMapYaml(const fs::path& yaml_path) {
  const YamlMap yaml(yaml_path);
  const MapSpec spec = ParseSpec(yaml, yaml_path);
  const GrayImage image = ReadMapImage(spec, yaml.source());
  OccupancyGrid grid(spec.resolution, spec.origin, image.width, image.height);
  const double maxval = image.maxval;
  for (int row = 0; row < image.height; ++row) {
    const int y = image.height - 1 - row;
    for (int x = 0; x < image.width; ++x) {
      const double v = image.at(x, row);
      const double p = spec.negate ? v / maxval : (maxval - v) / maxval;
      if (p > spec.occupied_thresh) {
        grid.SetCell(x, y, CellState::kOccupied);
      } else if (p < spec.free_thresh) {
        grid.SetCell(x, y, CellState::kFree);
      }
    }
  }
  grid.UpdateDistanceField();
  return grid;
}

std::string ReadMapYamlImageName(std::istream& yaml, const std::string& source) {
  return YamlMap::Unquote(
      YamlMap(yaml, source).Require("image", "the map image's file name").value);
}

void WriteMapYaml(const OccupancyGrid& grid, const fs::path& yaml) {
  fs::path pgm = yaml;
  pgm.replace_extension(".pgm");
  if (pgm == yaml) {
    throw Error(yaml.string() + ": map YAML path must not end in .pgm; the image goes there");
  }
  GrayImage image;
  image.width = grid.width();
  image.height = grid.height();
  image.pixels.reserve(static_cast<std::size_t>(image.width) * image.height);
  for (int row = 0; row < image.height; ++row) {
    const int y = image.height - 1 - row;
    for (int x = 0; x < image.width; ++x) {
      switch (grid.state(x, y)) {
        case CellState::kOccupied:
          image.pixels.push_back(kOccupiedValue);
          break;
        case CellState::kFree:
          image.pixels.push_back(kFreeValue);
          break;
        case CellState::kUnknown:
          image.pixels.push_back(kUnknownValue);
          break;
      }
    }
  }
  WritePgm(image, pgm);

  std::ofstream out(yaml);
  if (!out) throw Error(yaml.string() + ": cannot open for writing");
  out << "image: " << pgm.filename().string() << "\n"
      << "resolution: " << FormatShortest(grid.resolution()) << "\n"
      << "origin: [" << FormatShortest(grid.origin().x()) << ", "
      << FormatShortest(grid.origin().y()) << ", 0.0]\n"
      << "negate: 0\n"
      << "occupied_thresh: " << FormatShortest(kWrittenOccupiedThresh) << "\n"
      << "free_thresh: " << FormatShortest(kWrittenFreeThresh) << "\n";
  out.close();
  if (!out) throw Error(yaml.string() + ": write failed");
}

}  // namespace evoslam
