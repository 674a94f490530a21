// Ray casting: single rays through the LineMap index and the occupancy grid, and whole fans
// through the temporary-map sweep the estimator uses.
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>

#include "common/grid/occupancy_grid.h"
#include "common/localization/grid_renderer.h"
#include "common/localization/segment_renderer.h"
#include "common/sim/world.h"
#include "common/util/random.h"

namespace evoslam {
namespace {

// Unit directions at a stride that is not a simple fraction of a turn, so that consecutive rays
// hit different walls; precomputed so that the benchmarks time the casts, not sine and cosine.
// Ray i pairs origin i mod 1024 with a direction that shifts by one on each pass over the
// origins, so that no (origin, direction) pair repeats soon enough to be remembered.
std::vector<Eigen::Vector2d> Directions(std::size_t count) {
  std::vector<Eigen::Vector2d> directions;
  for (std::size_t i = 0; i < count; ++i) {
    const double angle = 0.377 * static_cast<double>(i);
    directions.emplace_back(std::cos(angle), std::sin(angle));
  }
  return directions;
}

// Ray origins spread over the route, where a robot would be.
std::vector<Eigen::Vector2d> Origins(const World& world, std::size_t count) {
  std::vector<Eigen::Vector2d> origins;
  Rng rng(7);
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t leg = rng.UniformIndex(world.waypoints.size() - 1);
    const double s = rng.Uniform();
    origins.push_back((1 - s) * world.waypoints[leg] + s * world.waypoints[leg + 1]);
  }
  return origins;
}

// Casts single 8 m rays through `map` (a LineMap or an OccupancyGrid) from the world's route.
template <typename Map>
void CastSingleRays(benchmark::State& state, const World& world, const Map& map) {
  const auto origins = Origins(world, 1024);
  const auto directions = Directions(1024);
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        map.CastRay(origins[i & 1023], directions[(i + (i >> 10)) & 1023], 8.0));
    ++i;
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()));
}

void BM_LineMapCastRay(benchmark::State& state, const char* name) {
  const World world = BuiltinWorld(name);
  CastSingleRays(state, world, world.map);
  state.counters["walls"] = static_cast<double>(world.map.size());
}
BENCHMARK_CAPTURE(BM_LineMapCastRay, office_boxes, "office-boxes");
BENCHMARK_CAPTURE(BM_LineMapCastRay, office_cluster, "office-cluster");

// A 5 cm grid rasterised from the world's walls.
OccupancyGrid RasterGrid(const World& world) {
  const Bounds& b = world.map.bounds();
  const double res = 0.05;
  OccupancyGrid grid(res, b.min - Eigen::Vector2d(1, 1),
                     static_cast<int>((b.max.x() - b.min.x() + 2) / res),
                     static_cast<int>((b.max.y() - b.min.y() + 2) / res));
  for (const Segment& s : world.map.segments()) {
    const int steps = static_cast<int>((s.b - s.a).norm() / (0.25 * res)) + 1;
    for (int k = 0; k <= steps; ++k) {
      const Eigen::Vector2d p = s.a + (s.b - s.a) * (static_cast<double>(k) / steps);
      if (const auto c = grid.WorldToCell(p)) grid.SetCell(c->x(), c->y(), CellState::kOccupied);
    }
  }
  grid.UpdateDistanceField();
  return grid;
}

void BM_GridCastRay(benchmark::State& state, const char* name) {
  const World world = BuiltinWorld(name);
  const OccupancyGrid grid = RasterGrid(world);
  CastSingleRays(state, world, grid);
  state.counters["cells"] = static_cast<double>(grid.width()) * grid.height();
}
BENCHMARK_CAPTURE(BM_GridCastRay, office_boxes, "office-boxes");
BENCHMARK_CAPTURE(BM_GridCastRay, office_cluster, "office-cluster");

// One fan as the 2D estimator renders it: 481 rays (180 degrees of beams plus +-30 degrees of
// heading at 0.5 degrees), items = rays.
void BM_SegmentRendererFan(benchmark::State& state, const char* name) {
  const World world = BuiltinWorld(name);
  const auto origins = Origins(world, 64);
  std::vector<SegmentRenderer> renderers;
  for (const auto& o : origins) renderers.emplace_back(TemporaryMap(world.map, o, 8.5));
  const RayFan fan(-2.0, 0.5 * std::numbers::pi / 180, 481);
  std::vector<float> rays(fan.size());
  std::size_t i = 0;
  for (auto _ : state) {
    renderers[i & 63].Render(origins[i & 63], fan, 8.0f, rays);
    benchmark::DoNotOptimize(rays.data());
    ++i;
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * fan.size()));
}
BENCHMARK_CAPTURE(BM_SegmentRendererFan, office_boxes, "office-boxes");
BENCHMARK_CAPTURE(BM_SegmentRendererFan, office_cluster, "office-cluster");

// The same fan cast ray by ray through the 5 cm grid of the office cluster, as localization in
// a grid map renders it.
void BM_GridRendererFan(benchmark::State& state) {
  const World world = BuiltinWorld("office-cluster");
  const OccupancyGrid grid = RasterGrid(world);
  const GridRenderer renderer(grid);
  const auto origins = Origins(world, 64);
  const RayFan fan(-2.0, 0.5 * std::numbers::pi / 180, 481);
  std::vector<float> rays(fan.size());
  std::size_t i = 0;
  for (auto _ : state) {
    renderer.Render(origins[i & 63], fan, 8.0f, rays);
    benchmark::DoNotOptimize(rays.data());
    ++i;
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * fan.size()));
}
BENCHMARK(BM_GridRendererFan);

}  // namespace
}  // namespace evoslam
