// attenuvis._attenuvis.visgraph.space_syntax*: the space-syntax measures
// (visgraph/space_syntax.hpp) as NumPy arrays, one row per sigma.  The pass
// and the measures run through watched_call: Ctrl-C stops the pass between
// rows and the measures between blocks of 512 nodes.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <cstdint>
#include <string>
#include <vector>

#include "attenuvis/visgraph/space_syntax.hpp"
#include "attenuvis/visgraph/work_estimate.hpp"
#include "bindings.hpp"
#include "watched_call.hpp"

namespace py = pybind11;
namespace vg = attenuvis::visgraph;

namespace attenuvis::python {
namespace {

vg::GraphStorage storage_of(const std::string& graph) {
  vg::GraphStorage storage = vg::GraphStorage::automatic;
  if (!vg::parse_graph_storage(graph, storage))
    throw std::invalid_argument("graph: expected 'auto', 'bit-rows' or 'csr', got '" + graph + "'");
  return storage;
}

vg::SpaceSyntaxOptions options(const std::vector<double>& sigmas, const std::string& measures, int radius,
                               double threshold, double spacing, const std::vector<std::uint32_t>& origins,
                               int threads, const std::string& graph) {
  vg::SpaceSyntaxOptions o;
  o.storage = storage_of(graph);
  o.sigmas = sigmas;
  o.measures = vg::parse_measures(measures);
  o.radius = radius;
  o.contrast_threshold = threshold;
  o.grid_spacing = spacing;
  o.depth_origins = origins;
  o.threads = threads;
  return o;
}

// {"measures": {name: (K, N) array}, "lines": [per condition], ...}.
py::dict to_dict(const vg::SpaceSyntaxResult& r, std::size_t K) {
  py::dict measures;
  for (const vg::SpaceSyntaxColumn& c : r.columns) {
    if (!measures.contains(c.measure.c_str())) {
      const std::size_t n = c.values.size();
      measures[c.measure.c_str()] = Doubles({static_cast<py::ssize_t>(K), static_cast<py::ssize_t>(n)});
    }
    auto array = measures[c.measure.c_str()].cast<py::array_t<double>>();
    double* p = array.mutable_data() + c.condition * c.values.size();
    std::copy(c.values.begin(), c.values.end(), p);
  }
  py::dict out;
  out["measures"] = measures;
  out["lines"] = r.edges;
  out["components"] = r.components;
  out["same_graph_as"] = r.same_graph_as;
  out["bit_rows"] = r.bit_rows;
  out["graph_bytes"] = r.graph_bytes;
  out["seconds"] = r.seconds;
  return out;
}

py::dict from_edges(const Doubles& eyes, const Indices& i, const Indices& j, const std::vector<double>& sigmas,
                    const std::string& measures, int radius, double threshold, double spacing,
                    const std::vector<std::uint32_t>& origins, int threads, const std::string& graph) {
  const std::vector<Eigen::Vector3d> e = points(eyes, "eyes");
  if (i.ndim() != 1 || j.ndim() != 1 || i.size() != j.size())
    throw std::invalid_argument("edges: i and j must be 1-D arrays of the same length");
  std::vector<vg::Edge> edges(static_cast<std::size_t>(i.size()));
  for (std::size_t k = 0; k < edges.size(); ++k) edges[k] = {i.data()[k], j.data()[k], 0.0};
  vg::SpaceSyntaxOptions o = options(sigmas, measures, radius, threshold, spacing, origins, threads, graph);
  std::atomic<bool> cancel{false};
  o.cancel = &cancel;
  const vg::SpaceSyntaxResult r = watched_call([&] { return vg::space_syntax(e, edges, o); }, cancel);
  return to_dict(r, sigmas.size());
}

py::dict from_scene(const vg::Scene& scene, const Doubles& eyes, const std::vector<double>& sigmas,
                    const std::string& measures, int radius, double threshold, double spacing,
                    const std::vector<std::uint32_t>& origins, int threads, const std::string& graph,
                    py::object progress) {
  const std::vector<Eigen::Vector3d> e = points(eyes, "eyes");
  vg::SpaceSyntaxOptions o = options(sigmas, measures, radius, threshold, spacing, origins, threads, graph);
  vg::VisibilityOptions pass;
  pass.sigmas = sigmas;
  pass.threads = threads;
  std::atomic<std::uint64_t> done{0};
  std::atomic<bool> cancel{false};
  pass.pairs_done = &done;
  pass.cancel = &cancel;
  o.cancel = &cancel;
  const vg::SpaceSyntaxRun run = watched_call([&] { return vg::space_syntax(scene, e, pass, o); }, cancel, [&] {
    if (!progress.is_none()) progress(done.load());
  });
  py::dict out = to_dict(run.measures, sigmas.size());
  out["degree"] = py::array_t<std::uint32_t>(run.pass.degree.size(), run.pass.degree.data());
  out["pass_seconds"] = run.pass.seconds;
  out["pairs_visible"] = run.pass.pairs_visible;
  return out;
}

}  // namespace

void bind_space_syntax(py::module_ module) {
  module.def("space_syntax_edges", &from_edges, py::arg("eyes"), py::arg("i"), py::arg("j"), py::arg("sigmas"),
             py::arg("measures"), py::arg("radius"), py::arg("threshold"), py::arg("spacing"), py::arg("origins"),
             py::arg("threads"), py::arg("graph"));
  module.def(
      "space_syntax",
      [](py::handle scene, const Doubles& eyes, const std::vector<double>& sigmas, const std::string& measures,
         int radius, double threshold, double spacing, const std::vector<std::uint32_t>& origins, int threads,
         const std::string& graph, py::object progress) {
        return from_scene(scene_of(scene), eyes, sigmas, measures, radius, threshold, spacing, origins, threads,
                          graph, progress);
      },
      py::arg("scene"), py::arg("eyes"), py::arg("sigmas"), py::arg("measures"), py::arg("radius"),
      py::arg("threshold"), py::arg("spacing"), py::arg("origins"), py::arg("threads"), py::arg("graph"),
      py::arg("progress"));
}

}  // namespace attenuvis::python
