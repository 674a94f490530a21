#include "common/slam/rss/rss_method.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/sim/simulator.h"
#include "common/sim/world.h"
#include "common/slam/rss/local_search.h"
#include "common/slam/slam_params.h"

namespace evoslam {
namespace {

proto::SlamParams WithCellSize(double cell_size) {
  proto::SlamParams params = WithDefaults({});
  params.mutable_rss()->mutable_map()->set_cell_size_m(cell_size);
  return params;
}

// The estimate follows the search map that the run builds: a quarter of the cell area takes four
// times the memory, and the message names the cells and the flag that sets them.
TEST(RssPeakMemoryTest, GrowsWithTheSearchMapsCells) {
  SimulationOptions sim;
  sim.max_scans = 20;
  const Dataset log = Simulate(BuiltinWorld("s-corridor"), sim);
  const RssMethod rss;
  const proto::SlamParams coarse = WithCellSize(0.04), fine = WithCellSize(0.02);
  const MemoryNeed at_coarse = rss.PeakMemory(log, coarse), at_fine = rss.PeakMemory(log, fine);
  const HitCountGrid map = EmptyMapFor(log, fine.rss().map(), fine.rss().local());
  const double cells = static_cast<double>(map.width()) * map.height();
  EXPECT_GE(static_cast<double>(at_fine.bytes), 4.0 * cells);
  EXPECT_LE(static_cast<double>(at_fine.bytes), 16.0 * cells);
  EXPECT_NEAR(static_cast<double>(at_fine.bytes) / static_cast<double>(at_coarse.bytes), 4.0, 0.2);
  EXPECT_THAT(at_fine.driver, ::testing::HasSubstr(std::to_string(map.width()) + " x " +
                                                   std::to_string(map.height()) + " cells"));
  EXPECT_THAT(at_fine.driver, ::testing::HasSubstr("--resolution"));
  // A map too large for any grid is still estimated, not refused or overflowed.
  EXPECT_GT(rss.PeakMemory(log, WithCellSize(1e-6)).bytes, 1'000'000'000'000u);
}

// The summary gives the cell size as set, however fine.
TEST(RssSummaryTest, NamesAFineCellSizeInFull) {
  proto::SlamReport report;
  *report.mutable_params() = WithCellSize(0.005);
  EXPECT_THAT(RssMethod().Summary(report), ::testing::HasSubstr("map cells 0.005 m,"));
}

}  // namespace
}  // namespace evoslam
