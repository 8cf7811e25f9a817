// Random lines of sight between nodes, decided by the visibility pass
// (Embree) and by the independent segment test of test_visibility_scenes.hpp,
// pair by pair.  Shared by the ground tests and the hillside benchmark
// (validation/bench/hillside_ground.cpp), so that both report the same check.
#pragma once

#include "test_visibility_scenes.hpp"

#include <attenuvis/visgraph/scene.hpp>
#include <attenuvis/visgraph/visibility.hpp>

#include <cstdint>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace vgtest {

struct SightCheck {
  std::size_t pairs = 0, visible = 0, agree = 0;
  std::size_t hidden_by_ground = 0;     // blocked in `mesh` but not in `buildings`
  std::vector<std::string> disagreements;  // the first few, described
};

// `groups` draws of `per_group` nodes from `nodes` (with `seed`); every pair
// of a draw (coincident ones left out) is decided by all_to_all on `scene`
// and by brute_force_visible on `mesh` (the same triangles), and by the
// segment test on `buildings` alone to count the pairs the ground hides.
inline SightCheck random_sight_lines(const attenuvis::visgraph::Scene& scene, const Mesh& mesh, const Mesh& buildings,
                                     const std::vector<Vector3d>& nodes, int groups, int per_group,
                                     std::uint64_t seed) {
  namespace vg = attenuvis::visgraph;
  SightCheck check;
  std::mt19937_64 rng(seed);
  for (int group = 0; group < groups; ++group) {
    std::vector<Vector3d> draw;
    for (int k = 0; k < per_group; ++k) draw.push_back(nodes[rng() % nodes.size()]);
    vg::VisibilityOptions options;
    options.sigmas = {0.0};
    std::set<std::pair<std::uint32_t, std::uint32_t>> seen;
    options.edge_sink = [&](const std::vector<vg::Edge>& edges) {
      for (const vg::Edge& e : edges) seen.insert({e.i, e.j});
    };
    vg::all_to_all(scene, draw, options);
    for (std::uint32_t i = 0; i < draw.size(); ++i)
      for (std::uint32_t j = i + 1; j < draw.size(); ++j) {
        if ((draw[i] - draw[j]).norm() < 1e-6) continue;  // the same node drawn twice
        const bool expected = brute_force_visible(mesh, draw[i], draw[j]);
        const bool agree = (seen.count({i, j}) == 1) == expected;
        ++check.pairs;
        check.visible += expected;
        check.agree += agree;
        check.hidden_by_ground += !expected && brute_force_visible(buildings, draw[i], draw[j]);
        if (!agree && check.disagreements.size() < 5)
          check.disagreements.push_back("draw " + std::to_string(group) + ": (" + std::to_string(draw[i].x()) + ", " +
                                        std::to_string(draw[i].y()) + ") to (" + std::to_string(draw[j].x()) + ", " +
                                        std::to_string(draw[j].y()) + "), segment test says " +
                                        (expected ? "visible" : "blocked"));
      }
  }
  return check;
}

}  // namespace vgtest
