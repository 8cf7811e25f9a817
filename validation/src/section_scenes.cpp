// The scenes: the seed's five classic 50 x 50 m layouts and its generated
// city, as 3D views in the manner of its Figs. vg_cases and vg_case_city.
// The meshes are the ones the visibility sections cast rays against; they are
// written as OBJ beside the report (a reader can open them in any 3D viewer)
// and the figure script draws them with its own projection.
#include "section_scenes.hpp"

#include <string>

#include <attenuvis/visgraph/mesh.hpp>

namespace attenuvis::validation::detail {

visgraph::CityOptions report_city_options(bool quick) {
  visgraph::CityOptions o;  // defaults: seed 2021, 4 rings (61 blocks)
  if (quick) o.rings = 1;
  return o;
}

void section_scenes(Context& ctx, Section& s) {
  namespace vg = attenuvis::visgraph;
  ctx.step("scenes", "writing the five layouts and the city as OBJ");
  nlohmann::json layout_panels = nlohmann::json::array();
  for (int k = 0; k < vg::kClassicLayoutCount; ++k) {
    const std::string file = "layout" + std::to_string(k) + ".obj";
    vg::write_obj(vg::classic_layout(k), ctx.dir + "/" + file);
    layout_panels.push_back({{"obj", file}, {"title", std::to_string(k) + " " + vg::classic_layout_name(k)}});
  }
  const vg::CityOptions copt = report_city_options(ctx.options.quick);
  const vg::City city = vg::make_city(copt);
  vg::write_obj(city.mesh, ctx.dir + "/city.obj");

  s.text("The seed analyses five classic layouts from the visibility-graph literature (Sec. Case Study Models: "
         "each a 50 x 50 m floor with obstacles extruded to 10 m, sampled at 1 m) and a city generated in "
         "CityEngine (hexagonal street network, 2 m sidewalks, varying terrain and building heights). The layouts "
         "are rebuilt here from their description; the seed's city is not published, so a city in its spirit is "
         "generated (" + std::to_string(city.blocks.size()) + " hexagonal blocks, " +
         format_number(copt.relief, 3) + " m of relief, buildings " + format_number(copt.building_height_min, 3) +
         "-" + format_number(copt.building_height_max, 3) + " m tall, 2 m sidewalks and crosswalks). Both are "
         "shown as the seed shows them, in 3D, and are beside this page as OBJ files." +
         (ctx.options.quick ? " QUICK MODE: a one-ring city." : ""));
  s.figure({"scenes_layouts",
            "The five layouts in 3D (seed Fig. vg_cases): grey floor 50 x 50 m, obstacles 10 m tall; numbered "
            "0-4 as in the rest of the report (the seed's 'third' layout is number 2).",
            {{"kind", "scene3d"}, {"panels", layout_panels}, {"ncols", 5}, {"panel_size", 2.6}}});
  s.figure({"scenes_city",
            "The generated city in 3D (compare seed Fig. vg_case_city): buildings, roads, sidewalks and "
            "crosswalks on rolling terrain; nodes are placed on the sidewalks and crosswalks.",
            {{"kind", "scene3d"},
             {"panels", {{{"obj", "city.obj"}, {"title", ""}}}},
             {"ncols", 1},
             {"panel_size", 6.5},
             {"legend", true}}});
  std::string layout_files;
  for (int k = 0; k < vg::kClassicLayoutCount; ++k) layout_files += "layout" + std::to_string(k) + ".obj ";
  s.data(layout_files, "the five layouts (0-4), triangles in metres");
  s.data("city.obj", "the city, triangles in metres, one group per surface kind (building, road, sidewalk, "
                     "crosswalk, ground, terrain)");
  s.summary.push_back("5 layouts and a city of " + std::to_string(city.blocks.size()) + " blocks (" +
                      std::to_string(city.mesh.triangles.size()) + " triangles) written as OBJ");
}

}  // namespace attenuvis::validation::detail
