// The performance section's table of floors: the engine against raw Embree
// casting every pair and against a raw vectorised scoring loop, in the same
// run, on an open plane (every pair in sight), the Delfshaven CityJSON (real
// LoD2 buildings) and the five layouts (visgraph_benchmark.hpp,
// compare_with_floors; the benchmark visgraph_throughput prints the same
// figures, docs/validation/benchmarks.md says how to rerun them).
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "attenuvis/validation/visgraph_benchmark.hpp"
#include "attenuvis/visgraph/cityjson.hpp"
#include "attenuvis/visgraph/generators.hpp"
#include "attenuvis/visgraph/mesh.hpp"
#include "attenuvis/visgraph/nodes.hpp"
#include "attenuvis/visgraph/scene.hpp"
#include "sections.hpp"

namespace attenuvis::validation::detail {

namespace {
namespace vg = attenuvis::visgraph;

// The real city: ../shared/data next to the source tree (absent: left out).
const char* const kDelfshaven = ATTENUVIS_SHARED_DATA_DIR "/cityjson/rotterdam-delfshaven-3-20.city.json";

struct Workload {
  std::string name, key;
  const vg::Scene* scene;
  std::vector<Eigen::Vector3d> eyes;
  std::vector<double> sigmas;
};

std::vector<Eigen::Vector3d> grid(const vg::Scene& scene, double spacing, std::vector<std::string> walkable) {
  vg::NodeGridOptions o;
  o.spacing = spacing;
  o.walkable = std::move(walkable);
  return vg::generate_nodes(scene, o).eyes;
}

vg::Mesh open_plane(double side) {
  vg::Mesh plane;
  plane.vertices = {{0, 0, 0}, {side, 0, 0}, {side, side, 0}, {0, side, 0}};
  plane.triangles = {{0, 1, 2}, {0, 2, 3}};
  plane.triangle_group = {0, 0};
  plane.groups = {"plane"};
  return plane;
}

void add_row(Table& t, const Workload& w, int threads, const FloorComparison& f) {
  const double pairs = static_cast<double>(f.pairs);
  t.add_row({w.name, f.nodes, f.pairs, static_cast<int>(w.sigmas.size()), threads,
             Cell(100.0 * static_cast<double>(f.culled_visible) / pairs, 3),
             Cell(100.0 * static_cast<double>(f.culled_blocked) / pairs, 3),
             Cell(100.0 * static_cast<double>(f.cast) / pairs, 3), Cell(f.cluster_s + f.packet_s, 3),
             Cell(f.score_s, 3), Cell(f.rays_s, 3), Cell(f.engine_cpu.best_s, 3), Cell(f.rays_cpu.best_s, 3),
             Cell(f.scoring_cpu.best_s, 3), Cell(f.over_rays(), 3), Cell(f.ceiling(), 3), Cell(f.over_scoring(), 3),
             f.engine_no_plane_cpu.best_s > 0 ? Cell(f.engine_no_plane_cpu.best_s, 3) : Cell("-"),
             f.over_rays_no_plane() > 0 ? Cell(f.over_rays_no_plane(), 3) : Cell("-"),
             f.engine_no_plane_cpu.best_s > 0 ? Cell(100.0 * static_cast<double>(f.cast_no_plane) / pairs, 3)
                                              : Cell("-")});
}
}  // namespace

void floors_table(Context& ctx, Section& s) {
  const bool quick = ctx.options.quick;
  const std::vector<double> four = seed_benchmark_sigmas(), one = {four.front()};
  const double side = quick ? 100.0 : 150.0, city_spacing = 12.0;
  s.text("The floors, in the same run on the same eye points: raw Embree casting every unordered pair as the "
         "engine's own packets, no scoring (what culling has to beat), and a raw scoring loop over every pair "
         "taken as in sight, distance and exp(-sigma d) vectorised by the compiler with glibc's vector exp, double "
         "sums to both ends, no rays (what in-sight scoring has to come near). Times are CPU seconds of the "
         "process (one run each), the engine's split by phase from the shares a phase-timed run measured. "
         "The engine stays exact: culling changes no result (the tests compare degree, S_S bits, distances and "
         "edges with casting every pair), and every pair keeps its own rounding to fixed point.");
  const vg::Scene plane(open_plane(side));
  std::vector<Workload> work;
  const std::string plane_name = "open plane " + format_number(side, 3) + " m, 1 m grid";
  work.push_back({plane_name, "plane_k1", &plane, grid(plane, 1.0, {}), one});
  work.push_back({plane_name, "plane_k4", &plane, work.back().eyes, four});
  std::unique_ptr<vg::Scene> city;
  if (std::filesystem::exists(kDelfshaven)) {
    vg::Mesh m = vg::load_cityjson(kDelfshaven);
    vg::add_ground_plane(m);
    city = std::make_unique<vg::Scene>(m);
    work.push_back({"Delfshaven CityJSON, " + format_number(city_spacing, 3) + " m grid", "delfshaven", city.get(),
                    grid(*city, city_spacing, {}), four});
  } else {
    s.missing(std::string("the Delfshaven CityJSON (") + kDelfshaven + ") is absent: no real-city row.");
  }
  std::vector<std::unique_ptr<vg::Scene>> layouts;
  for (int k = 0; k < vg::kClassicLayoutCount; ++k) {
    layouts.push_back(std::make_unique<vg::Scene>(vg::classic_layout(k)));
    work.push_back({std::to_string(k) + " " + vg::classic_layout_name(k) + ", 1 m grid", "layout" + std::to_string(k),
                    layouts.back().get(), grid(*layouts.back(), 1.0, vg::classic_layout_walkable_groups()), four});
  }
  Table t{"performance_floors",
          "The engine against both floors: pairs decided in sight, blocked or cast; CPU seconds in classification, "
          "scoring and rays; raw Embree time / engine time (above 1: faster than casting every pair); the most that ratio "
          "can be when each pair in sight costs what the raw scoring loop spends on it and no other pair costs "
          "anything (raw Embree time / (raw scoring time x the share of pairs in sight)); engine time / raw scoring "
          "time (1: as fast as the plain vectorised loop); the engine without its eyes' plane (which decides sight "
          "lines where every node stands at one height), raw Embree time / that engine time, and the pairs it cast (-: "
          "not run, the open plane has no walls and the engine would be the same)",
          {"workload", "nodes", "pairs", "conditions", "threads", "culled in sight [%]", "culled blocked [%]",
           "cast [%]", "classification [CPU s]", "scoring [CPU s]", "rays [CPU s]", "engine [CPU s]",
           "raw Embree [CPU s]", "raw scoring [CPU s]", "raw Embree / engine", "ceiling of raw Embree / engine",
           "engine / raw scoring", "engine without the eyes' plane [CPU s]", "raw Embree / engine without the plane",
           "cast without the plane [%]"},
          {},
          ""};
  for (const Workload& w : work) {
    ctx.step("performance", "floors: " + w.name + ", " + std::to_string(w.sigmas.size()) + " condition(s)");
    FloorOptions o;
    o.sigmas = w.sigmas;
    o.threads = ctx.threads;
    o.repeats = 1;
    o.without_eye_plane = w.key.compare(0, 5, "plane") != 0;  // the open plane has no walls: the same engine
    const FloorComparison f = compare_with_floors(*w.scene, w.eyes, o);
    add_row(t, w, ctx.threads, f);
    ctx.set("performance.floors." + w.key + ".speed_over_raw_embree", f.over_rays());
    ctx.set("performance.floors." + w.key + ".time_over_raw_scoring", f.over_scoring());
    if (w.key.compare(0, 6, "layout") != 0)
      s.summary.push_back("floors, " + w.name + " (" + std::to_string(w.sigmas.size()) + " condition(s)): " +
                          sig(f.over_rays(), 3) + "x raw Embree's speed, " + sig(f.over_scoring(), 3) +
                          "x the raw scoring loop's time");
  }
  add_table(ctx, s, t);
}

}  // namespace attenuvis::validation::detail
