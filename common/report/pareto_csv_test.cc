#include "common/report/pareto_csv.h"

#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "common/report/pareto_testing.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

using testing::MakeFront;
using testing::TwoWindowFronts;

using CsvRecord = std::vector<std::string>;

// The records of RFC 4180 text with lines ending in "\n", '#' lines left out: a quoted field may
// hold commas, line breaks and doubled quotes.
std::vector<CsvRecord> ParseCsv(std::string_view text) {
  std::vector<CsvRecord> records;
  std::size_t i = 0;
  while (i < text.size()) {
    if (text[i] == '#') {
      i = text.find('\n', i) + 1;
      continue;
    }
    CsvRecord record(1);
    bool quoted = false;
    for (; i < text.size(); ++i) {
      const char c = text[i];
      if (quoted && c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
        record.back() += '"';
        ++i;
      } else if (c == '"') {
        quoted = !quoted;
      } else if (!quoted && c == ',') {
        record.emplace_back();
      } else if (!quoted && c == '\n') {
        ++i;
        break;
      } else {
        record.back() += c;
      }
    }
    records.push_back(record);
  }
  return records;
}

double ParseValue(const std::string& text) {
  double v = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  EXPECT_TRUE(ec == std::errc() && end == text.data() + text.size()) << text;
  return v;
}

// The fronts as the CSV gives them back.
std::vector<ParetoFront> ReadBack(const std::vector<CsvRecord>& records) {
  const CsvRecord& header = records.at(0);
  const std::size_t objectives = header.size() - 4;
  std::vector<ParetoFront> fronts;
  for (std::size_t r = 1; r < records.size(); ++r) {
    const CsvRecord& rec = records[r];
    EXPECT_EQ(rec.size(), header.size());
    const auto front = static_cast<std::size_t>(std::stoul(rec[0]));
    if (front == fronts.size()) {
      fronts.push_back({.label = rec[1],
                        .objectives = CsvRecord(header.begin() + 3, header.end() - 1),
                        .f = Eigen::MatrixXd(static_cast<Eigen::Index>(objectives), 0),
                        .start = {},
                        .chosen = 0});
    }
    ParetoFront& f = fronts.at(front);
    EXPECT_EQ(f.label, rec[1]);
    const auto member = static_cast<Eigen::Index>(std::stoul(rec[2]));
    EXPECT_EQ(member, f.f.cols()) << "members in order";
    f.f.conservativeResize(Eigen::NoChange, member + 1);
    for (std::size_t o = 0; o < objectives; ++o) {
      f.f(static_cast<Eigen::Index>(o), member) = ParseValue(rec[3 + o]);
    }
    EXPECT_TRUE(rec.back() == "0" || rec.back() == "1") << rec.back();
    if (rec.back() == "1") f.chosen = static_cast<std::size_t>(member);
  }
  return fronts;
}

// Expects the same values bit for bit, NaN matching NaN.
void ExpectSameFronts(const std::vector<ParetoFront>& back,
                      const std::vector<ParetoFront>& fronts) {
  ASSERT_EQ(back.size(), fronts.size());
  for (std::size_t i = 0; i < fronts.size(); ++i) {
    EXPECT_EQ(back[i].label, fronts[i].label);
    EXPECT_EQ(back[i].objectives, fronts[i].objectives);
    EXPECT_EQ(back[i].chosen, fronts[i].chosen) << i;
    ASSERT_EQ(back[i].f.rows(), fronts[i].f.rows());
    ASSERT_EQ(back[i].f.cols(), fronts[i].f.cols());
    for (Eigen::Index o = 0; o < fronts[i].f.rows(); ++o) {
      for (Eigen::Index m = 0; m < fronts[i].f.cols(); ++m) {
        const double want = fronts[i].f(o, m);
        const double got = back[i].f(o, m);
        EXPECT_TRUE(std::isnan(want) ? std::isnan(got) : got == want)
            << i << " " << o << " " << m << ": " << got << " for " << want;
      }
    }
  }
}

TEST(ParetoCsvTest, ReadsBackAsTheFrontsWithTheirChosenMembers) {
  std::vector<ParetoFront> fronts = TwoWindowFronts();
  // Values whose shortest text is long, and ones far apart in size.
  fronts[0].f(0, 0) = 0.1 + 0.2;
  fronts[0].f(1, 2) = 1.0 / 3.0;
  fronts[1].f(2, 1) = 6.02214076e23;
  fronts[1].f(0, 2) = -4.9e-324;
  const std::string csv = ParetoCsv(fronts);
  ASSERT_EQ(csv.substr(0, 2), "# ");
  const std::vector<CsvRecord> records = ParseCsv(csv);
  EXPECT_EQ(records.at(0), (CsvRecord{"front", "label", "member", "consistency", "occupied cells",
                                      "empty cells", "chosen"}));
  EXPECT_EQ(records.size(), 1u + 3u + 3u) << "a line per member";
  ExpectSameFronts(ReadBack(records), fronts);
  int chosen = 0;
  for (std::size_t r = 1; r < records.size(); ++r) chosen += records[r].back() == "1";
  EXPECT_EQ(chosen, 2) << "one a front";
}

TEST(ParetoCsvTest, LabelsAndNamesThatHoldCommasQuotesOrBreaksAreQuoted) {
  const std::vector<ParetoFront> fronts = {
      MakeFront("window 3: scans 1,200-1,450", {{1.0, 2.0}, {0.5, 3.0}}, {}, 1,
                {"consistency, weighted", "cells \"occupied\""}),
      MakeFront("two\nlines", {{4.0, 5.0}}, {}, 0, {"consistency, weighted", "cells \"occupied\""}),
      MakeFront("plain", {{6.0, 7.0}}, {}, 0, {"consistency, weighted", "cells \"occupied\""})};
  const std::string csv = ParetoCsv(fronts);
  EXPECT_NE(csv.find(",\"window 3: scans 1,200-1,450\","), std::string::npos) << csv;
  EXPECT_NE(csv.find(",\"cells \"\"occupied\"\"\","), std::string::npos) << csv;
  EXPECT_NE(csv.find(",plain,"), std::string::npos) << "quoted only where needed\n" << csv;
  ExpectSameFronts(ReadBack(ParseCsv(csv)), fronts);
}

TEST(ParetoCsvTest, NonFiniteValuesAreWrittenAsTheyAre) {
  std::vector<ParetoFront> fronts = TwoWindowFronts();
  fronts[0].f(1, 1) = std::numeric_limits<double>::quiet_NaN();
  fronts[1].f(0, 2) = std::numeric_limits<double>::infinity();
  const std::vector<CsvRecord> records = ParseCsv(ParetoCsv(fronts));
  EXPECT_EQ(records.at(2).at(4), "nan");
  EXPECT_EQ(records.at(6).at(3), "inf");
  ExpectSameFronts(ReadBack(records), fronts);
}

TEST(ParetoCsvTest, OneObjectiveFrontsHaveOneValueColumn) {
  const std::vector<ParetoFront> fronts = {MakeFront("window 0", {{-3.25}}, {-3.0}, 0, {"fitness"}),
                                           MakeFront("window 1", {{-2.5}}, {-2.0}, 0, {"fitness"})};
  const std::vector<CsvRecord> records = ParseCsv(ParetoCsv(fronts));
  EXPECT_EQ(records.at(0), (CsvRecord{"front", "label", "member", "fitness", "chosen"}));
  ExpectSameFronts(ReadBack(records), fronts);
}

TEST(ParetoCsvTest, FrontsWithOtherObjectivesAreRefused) {
  std::vector<ParetoFront> fronts = TwoWindowFronts();
  fronts[1].objectives[0] = "fitness";
  EXPECT_THROW(ParetoCsv(fronts), Error);
  fronts = TwoWindowFronts();
  fronts[0].chosen = 5;
  EXPECT_THROW(ParetoCsv(fronts), Error);
}

}  // namespace
}  // namespace evoslam
