// `attenuvis scene`: writes a shipped scene to OBJ, or describes a scene file.
//   attenuvis scene layout:N|city[:SEED] --out FILE.obj [city options]
//   attenuvis scene info FILE [--groups] [--up-axis y] [--lod L]
// Both print triangles, bounding box, classes and groups (a count and the
// largest few; --groups: every group, sorted, with its triangles and classes).  The scenes themselves live
// in the visgraph library (generators.hpp); this file only parses arguments.
#include "commands.hpp"

#include "attenuvis/visgraph/generators.hpp"
#include "attenuvis/visgraph/mesh.hpp"
#include "attenuvis/visgraph/obj.hpp"
#include "attenuvis/visgraph/scene_file.hpp"

#include <algorithm>

#include <cstdio>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>

namespace attenuvis::cli {

// Called by register_visgraph (cmd_visgraph.cpp).
void register_scene_command(CLI::App& app);

namespace {

namespace vg = attenuvis::visgraph;

void print_group_line(const vg::MeshStats::Group& g) {
  std::string classes;
  for (const std::string& c : g.classes) classes += (classes.empty() ? "  [" : ", ") + c;
  if (!classes.empty()) classes += "]";
  std::printf("  %-24s %9zu triangles %14.1f m^2%s\n", g.name.c_str(), g.triangles, g.projected_area, classes.c_str());
}

void print_stats(const vg::Mesh& mesh, bool all_groups) {
  const vg::MeshStats stats = vg::mesh_stats(mesh);
  std::printf("triangles: %zu\nvertices: %zu\n", stats.triangles, stats.vertices);
  std::printf("bbox: [%.3f, %.3f] x [%.3f, %.3f] x [%.3f, %.3f] m\n", stats.lower.x(), stats.upper.x(),
              stats.lower.y(), stats.upper.y(), stats.lower.z(), stats.upper.z());
  if (!mesh.crs.empty()) std::printf("crs: %s\n", mesh.crs.c_str());
  // Projected area sums every triangle's xy footprint: a closed solid
  // (roof + floor) counts twice, walls not at all.
  if (!stats.classes.empty()) {
    std::printf("classes: %zu (name, triangles, xy-projected area)\n", stats.classes.size());
    for (const auto& c : stats.classes) print_group_line(c);
  }
  std::vector<vg::MeshStats::Group> groups = stats.groups;
  if (all_groups) {
    std::sort(groups.begin(), groups.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
    std::printf("groups: %zu, sorted by name (name, triangles, xy-projected area of all its triangles, classes)\n",
                groups.size());
    for (const auto& g : groups) print_group_line(g);
    return;
  }
  constexpr std::size_t shown = 12;
  std::stable_sort(groups.begin(), groups.end(), [](const auto& a, const auto& b) { return a.triangles > b.triangles; });
  std::printf("groups: %zu%s (name, triangles, xy-projected area of all its triangles, classes)\n", groups.size(),
              groups.size() > shown ? ", the largest 12" : "");
  for (std::size_t k = 0; k < groups.size() && k < shown; ++k) print_group_line(groups[k]);
  if (groups.size() > shown) std::printf("  ... and %zu more (--groups lists them all)\n", groups.size() - shown);
}

struct SceneArgs {
  std::string what;  // "info" or a scene spec
  std::string file;  // the OBJ to describe (info)
  std::string out;
  bool all_groups = false;
  std::string up_axis = "z", lod;
  vg::CityOptions city;
};

void run_scene(const SceneArgs& a) {
  if (a.what == "info") {
    if (a.file.empty()) throw std::invalid_argument("scene info: give the scene file to describe");
    vg::SceneFileOptions options;
    options.obj_up_axis = vg::parse_up_axis(a.up_axis);
    options.lod = a.lod;
    const vg::SceneFile file = vg::load_scene_file(a.file, options);
    std::printf("format: %s\n", file.format.c_str());
    for (const std::string& w : file.warnings) std::fprintf(stderr, "warning: %s: %s\n", a.file.c_str(), w.c_str());
    print_stats(file.mesh, a.all_groups);
    return;
  }
  if (!vg::is_scene_spec(a.what))
    throw std::invalid_argument("scene: unknown scene '" + a.what + "' (expected layout:0..4, city, city:SEED or info)");
  if (!a.file.empty()) throw std::invalid_argument("scene: unexpected argument '" + a.file + "' (use --out FILE)");
  if (a.out.empty()) throw std::invalid_argument("scene " + a.what + ": --out FILE.obj is required");
  const vg::Mesh mesh = vg::scene_from_spec(a.what, a.city);  // validates the spec and options
  vg::write_obj(mesh, a.out);
  // One line: what was written.  `scene info FILE` describes the file, so the
  // two commands in a row do not print the same description twice.
  std::printf("scene: %s -> %s: %zu triangles, %zu groups: %s (attenuvis scene info %s describes it)\n",
              a.what.c_str(), a.out.c_str(), mesh.triangles.size(), mesh.groups.size(),
              vg::preview_names(mesh.groups, 6, "").c_str(), a.out.c_str());
  if (a.what.rfind("city", 0) == 0) {
    std::printf("sidewalk+crosswalk: %.1f m^2 projected (closed form %.1f m^2)\n",
                vg::walkable_area(mesh, vg::city_walkable_groups()), vg::city_walkable_area_estimate(a.city));
  }
  if (a.all_groups) print_stats(mesh, true);
}

}  // namespace

void register_scene_command(CLI::App& app) {
  auto args = std::make_shared<SceneArgs>();
  CLI::App* scene = app.add_subcommand(
      "scene", "write a shipped scene (layout:0..4, city) as OBJ, or describe a scene file (info FILE)");
  scene->add_option("scene", args->what, "layout:N (N = 0..4), city, city:SEED, or info")->required();
  scene->add_option("file", args->file, "with info: the scene file to describe (CityJSON, glTF, OBJ)");
  scene->add_flag("--groups", args->all_groups, "list every group, sorted by name, with triangles and classes");
  scene->add_option("--up-axis", args->up_axis, "with info: up axis of an OBJ file, z or y")->capture_default_str();
  scene->add_option("--lod", args->lod, "with info: CityJSON level of detail (default: each object's highest)");
  scene->add_option("--out,-o", args->out, "OBJ file to write (atomically)");
  auto* c = &args->city;
  const std::string city_group = "City options (city scenes only)";
  scene->add_option("--rings", c->rings, "rings of hexagonal blocks around the central one, 0 to 40")
      ->capture_default_str()->group(city_group);
  scene->add_option("--hex-size", c->hex_size, "street centre-line hexagon side, (0, 1000] m")
      ->capture_default_str()->group(city_group);
  scene->add_option("--road-width", c->road_width, "m, curb to curb, (0, 100]")->capture_default_str()->group(city_group);
  scene->add_option("--sidewalk-width", c->sidewalk_width, "m, (0, 100]")->capture_default_str()->group(city_group);
  scene->add_option("--crosswalk-width", c->crosswalk_width, "m along the street, (0, 100]")
      ->capture_default_str()->group(city_group);
  scene->add_option("--relief", c->relief, "terrain peak to trough, [0, 1000] m")->capture_default_str()->group(city_group);
  scene->add_option("--park-fraction", c->park_fraction, "share of blocks left open, [0, 1]")
      ->capture_default_str()->group(city_group);
  scene->callback([args] { run_scene(*args); });
}

}  // namespace attenuvis::cli
