// `attenuvis scene`: writes a shipped scene to OBJ, or describes any OBJ.
//   attenuvis scene layout:N|city[:SEED] --out FILE.obj [city options]
//   attenuvis scene info FILE.obj
// Both print triangles, bounding box and groups.  The scenes themselves live
// in the visgraph library (generators.hpp); this file only parses arguments.
#include "commands.hpp"

#include "attenuvis/visgraph/generators.hpp"
#include "attenuvis/visgraph/mesh.hpp"
#include "attenuvis/visgraph/obj.hpp"

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

void print_stats(const vg::Mesh& mesh) {
  const vg::MeshStats stats = vg::mesh_stats(mesh);
  std::printf("triangles: %zu\nvertices: %zu\n", stats.triangles, stats.vertices);
  std::printf("bbox: [%.3f, %.3f] x [%.3f, %.3f] x [%.3f, %.3f] m\n", stats.lower.x(), stats.upper.x(),
              stats.lower.y(), stats.upper.y(), stats.lower.z(), stats.upper.z());
  // Projected area sums every triangle's xy footprint: a closed solid
  // (roof + floor) counts twice, walls not at all.
  std::printf("groups: %zu (name, triangles, xy-projected area of all its triangles)\n", stats.groups.size());
  for (const auto& g : stats.groups)
    std::printf("  %-12s %9zu triangles %14.1f m^2\n", g.name.c_str(), g.triangles, g.projected_area);
}

struct SceneArgs {
  std::string what;  // "info" or a scene spec
  std::string file;  // the OBJ to describe (info)
  std::string out;
  vg::CityOptions city;
};

void run_scene(const SceneArgs& a) {
  if (a.what == "info") {
    if (a.file.empty()) throw std::invalid_argument("scene info: give the OBJ file to describe");
    print_stats(vg::load_obj(a.file));
    return;
  }
  if (!vg::is_scene_spec(a.what))
    throw std::invalid_argument("scene: unknown scene '" + a.what + "' (expected layout:0..4, city, city:SEED or info)");
  if (!a.file.empty()) throw std::invalid_argument("scene: unexpected argument '" + a.file + "' (use --out FILE)");
  if (a.out.empty()) throw std::invalid_argument("scene " + a.what + ": --out FILE.obj is required");
  const vg::Mesh mesh = vg::scene_from_spec(a.what, a.city);  // validates the spec and options
  vg::write_obj(mesh, a.out);
  std::printf("scene: %s -> %s\n", a.what.c_str(), a.out.c_str());
  if (a.what.rfind("city", 0) == 0) {
    std::printf("sidewalk+crosswalk: %.1f m^2 projected (closed form %.1f m^2)\n",
                vg::walkable_area(mesh, vg::city_walkable_groups()), vg::city_walkable_area_estimate(a.city));
  }
  print_stats(mesh);
}

}  // namespace

void register_scene_command(CLI::App& app) {
  auto args = std::make_shared<SceneArgs>();
  CLI::App* scene = app.add_subcommand(
      "scene", "Write a shipped scene (layout:0..4, city, city:SEED) to OBJ, or describe an OBJ (info FILE)");
  scene->add_option("scene", args->what, "layout:N (N = 0..4), city, city:SEED, or info")->required();
  scene->add_option("file", args->file, "with info: the OBJ file to describe");
  scene->add_option("--out,-o", args->out, "OBJ file to write (atomically)");
  auto* c = &args->city;
  const std::string city_group = "City options (city scenes only)";
  scene->add_option("--rings", c->rings, "rings of hexagonal blocks around the central one")
      ->capture_default_str()->group(city_group);
  scene->add_option("--hex-size", c->hex_size, "street centre-line hexagon side, m")
      ->capture_default_str()->group(city_group);
  scene->add_option("--road-width", c->road_width, "m, curb to curb")->capture_default_str()->group(city_group);
  scene->add_option("--sidewalk-width", c->sidewalk_width, "m")->capture_default_str()->group(city_group);
  scene->add_option("--crosswalk-width", c->crosswalk_width, "m along the street")
      ->capture_default_str()->group(city_group);
  scene->add_option("--relief", c->relief, "terrain peak to trough, m")->capture_default_str()->group(city_group);
  scene->add_option("--park-fraction", c->park_fraction, "share of blocks left open")
      ->capture_default_str()->group(city_group);
  scene->callback([args] { run_scene(*args); });
}

}  // namespace attenuvis::cli
