// attenuvis._attenuvis.visgraph: scenes, node grids and the visibility pass
// over NumPy arrays.
//
// A visibility pass runs through watched_call (watched_call.hpp): Ctrl-C or
// an exception from the user's progress callback sets the pass's cancel flag,
// the pass stops after the rows in flight and the exception goes on to Python.
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "attenuvis/visgraph/gis/city.hpp"
#include "attenuvis/visgraph/ground.hpp"
#include "attenuvis/visgraph/layouts.hpp"
#include "attenuvis/visgraph/mesh.hpp"
#include "attenuvis/visgraph/nodes.hpp"
#include "attenuvis/visgraph/scene.hpp"
#include "attenuvis/visgraph/scene_file.hpp"
#include "attenuvis/visgraph/scene_spec.hpp"
#include "attenuvis/visgraph/visibility.hpp"
#include "bindings.hpp"
#include "watched_call.hpp"

namespace py = pybind11;
namespace vg = attenuvis::visgraph;

namespace attenuvis::python {
namespace {

// A built scene and what the Python layer shows of it.
struct PyScene {
  std::unique_ptr<vg::Scene> scene;
  std::vector<std::string> default_walkable;  // shipped scenes: their walkable groups
  std::string format, crs;
  std::vector<std::string> warnings;
  std::string ground;  // where the ground came from, when one was added (a DEM, inferred, a plane)
};

PyScene build(vg::Mesh mesh, std::vector<std::string> walkable, std::string format) {
  PyScene s;
  s.crs = mesh.crs;
  {
    py::gil_scoped_release release;
    s.scene = std::make_unique<vg::Scene>(mesh);
  }
  s.default_walkable = std::move(walkable);
  s.format = std::move(format);
  return s;
}

// A scene file or a footprint layer, on a DEM (`terrain` a path), on the
// ground inferred from its building bases (`terrain` "infer", ground.hpp) or
// as it is ("").
PyScene scene_from_city(const std::string& path, vg::gis::CityOptions options, const std::string& terrain) {
  const bool infer = terrain == "infer";
  if (!infer) options.terrain = terrain;
  vg::gis::CityModel city;
  std::string ground;
  {
    py::gil_scoped_release release;
    city = vg::gis::load_city(path, options);
    ground = city.ground;
    if (infer) ground = vg::add_ground(city.mesh, {}).description;
  }
  PyScene s = build(std::move(city.mesh), {}, city.format);
  s.warnings = city.warnings;
  s.ground = ground;
  return s;
}

PyScene scene_from_file(const std::string& path, const std::string& up_axis, const std::string& lod,
                        const std::string& terrain) {
  vg::gis::CityOptions options;
  options.file.obj_up_axis = vg::parse_up_axis(up_axis);
  options.file.lod = lod;
  return scene_from_city(path, options, terrain);
}

PyScene scene_from_footprints(const std::string& path, const std::string& height_field,
                              const std::string& levels_field, double storey_height, const std::string& terrain,
                              bool strict, double plane_z) {
  vg::gis::CityOptions options;
  options.footprints.height_field = height_field;
  options.footprints.levels_field = levels_field;
  options.footprints.storey_height = storey_height;
  options.footprints.strict = strict;
  options.plane_z = plane_z;
  return scene_from_city(path, options, terrain);
}

PyScene scene_from_spec(const std::string& spec) {
  return build(vg::scene_from_spec(spec), vg::default_walkable_groups(spec), spec);
}


Doubles to_array(const std::vector<Eigen::Vector3d>& v) {
  Doubles out({static_cast<py::ssize_t>(v.size()), py::ssize_t{3}});
  double* p = out.mutable_data();
  for (std::size_t i = 0; i < v.size(); ++i)
    for (int c = 0; c < 3; ++c) p[3 * i + c] = v[i][c];
  return out;
}

PyScene scene_from_arrays(const Doubles& vertices, const Indices& triangles, const Indices& groups,
                          const std::vector<std::string>& group_names) {
  vg::Mesh mesh;
  mesh.vertices = points(vertices, "vertices");
  if (triangles.ndim() != 2 || triangles.shape(1) != 3)
    throw std::invalid_argument("triangles: expected an (M, 3) array of vertex indices");
  const std::size_t T = static_cast<std::size_t>(triangles.shape(0));
  if (static_cast<std::size_t>(groups.size()) != T)
    throw std::invalid_argument("groups: expected one group per triangle");
  const std::uint32_t* t = triangles.data();
  const std::uint32_t* g = groups.data();
  for (const auto& name : group_names) mesh.add_group(name);
  mesh.triangles.resize(T);
  mesh.triangle_group.resize(T);
  for (std::size_t i = 0; i < T; ++i) {
    for (int c = 0; c < 3; ++c) {
      if (t[3 * i + c] >= mesh.vertices.size())
        throw std::invalid_argument("triangle " + std::to_string(i) + ": vertex index " +
                                    std::to_string(t[3 * i + c]) + " is out of range (" +
                                    std::to_string(mesh.vertices.size()) + " vertices)");
      mesh.triangles[i][c] = t[3 * i + c];
    }
    if (g[i] >= mesh.groups.size())
      throw std::invalid_argument("triangle " + std::to_string(i) + ": group index out of range");
    mesh.triangle_group[i] = g[i];
  }
  return build(std::move(mesh), {}, "arrays");
}

Doubles node_grid(const PyScene& s, double spacing, py::object walkable, double eye_height, double max_slope_deg) {
  vg::NodeGridOptions options;
  options.spacing = spacing;
  options.eye_height = eye_height;
  options.max_slope_deg = max_slope_deg;
  options.walkable = walkable.is_none() ? s.default_walkable : walkable.cast<std::vector<std::string>>();
  vg::NodeSet set;
  {
    py::gil_scoped_release release;
    set = vg::generate_nodes(*s.scene, options);
  }
  return to_array(set.eyes);
}

// Runs `pass` through watched_call (watched_call.hpp), reporting the pairs
// done to `progress` every 0.5 s and once at the end.
template <class Pass>
vg::VisibilityResult watched(Pass pass, vg::VisibilityOptions& options, py::object progress) {
  std::atomic<std::uint64_t> done{0};
  std::atomic<bool> cancel{false};
  options.pairs_done = &done;
  options.cancel = &cancel;
  auto last_report = std::chrono::steady_clock::now();
  vg::VisibilityResult result = watched_call([&] { return pass(options); }, cancel, [&] {
    const auto now = std::chrono::steady_clock::now();
    if (!progress.is_none() && now - last_report > std::chrono::milliseconds(500)) {
      last_report = now;
      progress(done.load());
    }
  });
  if (!progress.is_none()) progress(done.load());
  return result;
}

py::dict pass_result(const vg::VisibilityResult& r, std::size_t K) {
  const std::size_t N = r.nodes;
  py::dict out;
  Doubles sum({static_cast<py::ssize_t>(K), static_cast<py::ssize_t>(N)});
  double* p = sum.mutable_data();
  for (std::size_t k = 0; k < K; ++k) std::copy(r.sum[k].begin(), r.sum[k].end(), p + k * N);
  out["sum"] = sum;
  out["degree"] = r.degree_exact ? py::object(py::array_t<std::uint32_t>(r.degree.size(), r.degree.data()))
                                 : py::object(py::none());
  out["pruned"] = py::array_t<std::uint32_t>(r.pruned.size(), r.pruned.data());
  out["mean_distance"] = r.mean_distance.empty() ? py::object(py::none())
                                                 : py::object(Doubles(r.mean_distance.size(), r.mean_distance.data()));
  out["max_distance"] = r.max_distance.empty() ? py::object(py::none())
                                               : py::object(Doubles(r.max_distance.size(), r.max_distance.data()));
  out["prune_below"] = r.prune_below;
  out["pruning_radius"] = r.pruning_radius;
  out["pruning_note"] = r.pruning_note;
  out["pairs_culled_visible"] = r.pairs_culled_visible;
  out["pairs_culled_blocked"] = r.pairs_culled_blocked;
  out["pairs_total"] = r.pairs_total;
  out["pairs_cast"] = r.pairs_cast;
  out["pairs_visible"] = r.pairs_visible;
  out["coincident_pairs"] = r.coincident_pairs;
  out["seconds"] = r.seconds;
  return out;
}

// A NumPy array that takes over the vector's memory (no copy: the edge list
// of a large graph is the biggest thing a pass returns).
template <class T>
py::array_t<T> take(std::vector<T>&& v) {
  auto* owned = new std::vector<T>(std::move(v));
  py::capsule owner(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>(static_cast<py::ssize_t>(owned->size()), owned->data(), owner);
}

// Edges collected on the worker thread (the sink is called there, without
// the GIL), handed to NumPy at the end without a copy.
struct EdgeArrays {
  std::vector<std::uint32_t> i, j;
  std::vector<double> distance;
};

py::dict run(const PyScene& s, const std::vector<Eigen::Vector3d>& sources,
             const std::vector<Eigen::Vector3d>* targets, const std::vector<double>& sigmas, double prune_below,
             double max_distance, bool distance_stats, int threads, bool edges, py::object progress) {
  vg::VisibilityOptions options;
  options.sigmas = sigmas;
  options.prune_below = prune_below;
  options.max_distance = max_distance;
  options.distance_stats = distance_stats;
  options.threads = threads;
  EdgeArrays collected;
  if (edges)
    options.edge_sink = [&collected](const std::vector<vg::Edge>& block) {
      for (const auto& e : block) {
        collected.i.push_back(e.i);
        collected.j.push_back(e.j);
        collected.distance.push_back(e.distance);
      }
    };
  const vg::Scene& scene = *s.scene;
  const auto result = watched(
      [&](const vg::VisibilityOptions& o) {
        return targets ? vg::to_targets(scene, sources, *targets, o) : vg::all_to_all(scene, sources, o);
      },
      options, progress);
  py::dict out = pass_result(result, sigmas.size());
  if (edges) {
    out["edge_i"] = take(std::move(collected.i));
    out["edge_j"] = take(std::move(collected.j));
    out["edge_distance"] = take(std::move(collected.distance));
  }
  return out;
}

}  // namespace

std::vector<Eigen::Vector3d> points(const Doubles& array, const char* what) {
  if (array.ndim() != 2 || array.shape(1) != 3)
    throw std::invalid_argument(std::string(what) + ": expected an (N, 3) array of x, y, z in metres");
  const double* p = array.data();
  std::vector<Eigen::Vector3d> out(static_cast<std::size_t>(array.shape(0)));
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = {p[3 * i], p[3 * i + 1], p[3 * i + 2]};
  return out;
}

const vg::Scene& scene_of(py::handle scene) { return *scene.cast<const PyScene&>().scene; }

void bind_visgraph(py::module_ module) {
  py::class_<PyScene>(module, "Scene")
      .def_static("from_file", &scene_from_file, py::arg("path"), py::arg("up_axis") = "z", py::arg("lod") = "",
                  py::arg("terrain") = "")
      .def_static("from_footprints", &scene_from_footprints, py::arg("path"), py::arg("height_field"),
                  py::arg("levels_field"), py::arg("storey_height"), py::arg("terrain"), py::arg("strict"),
                  py::arg("plane_z"))
      .def_static("from_spec", &scene_from_spec, py::arg("spec"))
      .def_static("from_arrays", &scene_from_arrays, py::arg("vertices"), py::arg("triangles"), py::arg("groups"),
                  py::arg("group_names"))
      .def_property_readonly("triangle_count", [](const PyScene& s) { return s.scene->triangle_count(); })
      .def_property_readonly("bounds",
                             [](const PyScene& s) {
                               const auto& b = s.scene->bounds();
                               return to_array({b.min, b.max});
                             })
      .def_property_readonly("groups",
                             [](const PyScene& s) {
                               std::vector<std::string> names;
                               for (const auto& g : s.scene->groups()) names.push_back(g.name);
                               return names;
                             })
      .def_property_readonly("default_walkable", [](const PyScene& s) { return s.default_walkable; })
      .def_property_readonly("format", [](const PyScene& s) { return s.format; })
      .def_property_readonly("crs", [](const PyScene& s) { return s.crs; })
      .def_property_readonly("warnings", [](const PyScene& s) { return s.warnings; })
      .def_property_readonly("ground", [](const PyScene& s) { return s.ground; });

  module.def("node_grid", &node_grid, py::arg("scene"), py::arg("spacing"), py::arg("walkable"),
             py::arg("eye_height"), py::arg("max_slope_deg"));
  module.def(
      "all_to_all",
      [](const PyScene& s, const Doubles& eyes, const std::vector<double>& sigmas, double prune_below,
         double max_distance, bool distance_stats, int threads, bool edges, py::object progress) {
        const auto e = points(eyes, "eyes");
        return run(s, e, nullptr, sigmas, prune_below, max_distance, distance_stats, threads, edges, progress);
      },
      py::arg("scene"), py::arg("eyes"), py::arg("sigmas"), py::arg("prune_below"), py::arg("max_distance"),
      py::arg("distance_stats"), py::arg("threads"), py::arg("edges"), py::arg("progress"));
  module.def(
      "to_targets",
      [](const PyScene& s, const Doubles& sources, const Doubles& targets, const std::vector<double>& sigmas,
         double prune_below, double max_distance, bool distance_stats, int threads, bool edges, py::object progress) {
        const auto a = points(sources, "sources");
        const auto b = points(targets, "targets");
        return run(s, a, &b, sigmas, prune_below, max_distance, distance_stats, threads, edges, progress);
      },
      py::arg("scene"), py::arg("sources"), py::arg("targets"), py::arg("sigmas"), py::arg("prune_below"),
      py::arg("max_distance"), py::arg("distance_stats"), py::arg("threads"), py::arg("edges"),
      py::arg("progress"));
  module.def("classic_layout_name", &vg::classic_layout_name, py::arg("index"));
}

}  // namespace attenuvis::python
