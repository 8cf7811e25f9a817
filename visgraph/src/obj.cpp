// OBJ input and output for Mesh.
//
// Reading is split in two passes over the file held in memory:
//  1. our own light scan of the `v`, `f` and `usemtl` lines.  It exists for
//     three reasons tinyobjloader cannot cover: it names the line of a bad
//     vertex (NaN/inf, missing coordinate) or a bad face index (zero, out of
//     range), it parses coordinates with strtod, which rounds correctly
//     (tinyobjloader's own parser sums digit*0.1^k and loses the last bits of
//     UTM-sized coordinates such as 512345.67890123), and it collects the
//     `usemtl` names so they survive even without an .mtl file;
//  2. tinyobjloader proper, for polygon triangulation, groups and per-face
//     materials.  A synthetic `mtllib` line is prepended so that every
//     `usemtl` name gets a material id even when the file's .mtl is missing
//     (material properties are never needed, only the names).
//
// Naming rule (documented in obj.hpp): a triangle's group is its OBJ group
// (`g`, or `o` where the file uses objects); a triangle with no group takes
// its material name (`usemtl`); one with neither is in group "default".
#include <attenuvis/visgraph/limits.hpp>
#include <attenuvis/visgraph/obj.hpp>

#include <attenuvis/io/input_file.hpp>
#include <attenuvis/io/number_text.hpp>
#include <attenuvis/io/staged_file.hpp>

#include <tiny_obj_loader.h>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string_view>

namespace attenuvis::visgraph {

namespace {

constexpr const char* kMaterialSentinel = "attenuvis-usemtl-names.mtl";

[[noreturn]] void fail(const std::string& path, std::size_t line, const std::string& what) {
  std::ostringstream msg;
  msg << path;
  if (line > 0) msg << ":" << line;
  msg << ": " << what;
  throw std::runtime_error(msg.str());
}

std::string_view trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string_view::npos) return {};
  const auto last = s.find_last_not_of(" \t\r\n");
  return s.substr(first, last - first + 1);
}

// Result of the first pass (see the file comment).
struct Prescan {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::string> material_names;  // every `usemtl` name, first-seen order
  std::size_t faces = 0;
};

// Splits on "\n", "\r\n" or a lone "\r", as tinyobjloader's safeGetline does,
// so that our line numbers are the ones an editor shows.
template <typename F>
void for_each_line(const std::string& text, F&& visit) {
  std::size_t pos = 0, line = 0;
  while (pos < text.size()) {
    std::size_t end = text.find_first_of("\r\n", pos);
    if (end == std::string::npos) end = text.size();
    visit(++line, std::string_view(text).substr(pos, end - pos));
    if (end < text.size() && text[end] == '\r' && end + 1 < text.size() && text[end + 1] == '\n')
      ++end;
    pos = end + 1;
  }
}

Prescan prescan(const std::string& path, const std::string& text) {
  Prescan scan;
  std::set<std::string> seen_materials;
  long long largest_index = 0;  // largest positive vertex index and its line
  std::size_t largest_index_line = 0;
  for_each_line(text, [&](std::size_t line, std::string_view raw) {
    if (raw.size() > kMaxLineBytes)
      fail(path, line, "line of " + std::to_string(raw.size()) + " bytes, longer than the " +
                           std::to_string(kMaxLineBytes) + " an OBJ line may have");
    const std::string_view s = trim(raw);
    if (s.size() < 2 || s[0] == '#') return;
    const bool blank_after_keyword_1 = s[1] == ' ' || s[1] == '\t';
    if (s[0] == 'v' && blank_after_keyword_1) {
      // strtod needs a NUL-terminated string; lines are short.
      const std::string copy(s.substr(2));
      const char* p = copy.c_str();
      double xyz[3];
      for (int k = 0; k < 3; ++k) {
        char* end = nullptr;
        errno = 0;
        xyz[k] = std::strtod(p, &end);
        if (end == p) fail(path, line, "vertex needs three numeric coordinates: '" + std::string(s) + "'");
        if (!std::isfinite(xyz[k]))
          fail(path, line, "vertex coordinate is not finite (NaN or inf): '" + std::string(s) + "'");
        if (std::abs(xyz[k]) > kMaxCoordinate)
          fail(path, line, "vertex coordinate " + io::significant(xyz[k], 6) +
                               " is outside [-1e7, 1e7] m (shift the model nearer its origin)");
        p = end;
      }
      scan.vertices.emplace_back(xyz[0], xyz[1], xyz[2]);
    } else if (s[0] == 'f' && blank_after_keyword_1) {
      std::istringstream tokens{std::string(s.substr(2))};
      std::string token;
      int corners = 0;
      while (tokens >> token) {
        const char* begin = token.c_str();
        long long index = 0;
        const auto [ptr, ec] = std::from_chars(begin, begin + token.size(), index);
        if (ec != std::errc() || (ptr != begin + token.size() && *ptr != '/'))
          fail(path, line, "malformed face vertex '" + token + "'");
        if (index == 0) fail(path, line, "face vertex index 0 (OBJ indices start at 1)");
        const auto defined = static_cast<long long>(scan.vertices.size());
        if (index < 0 && -index > defined)
          fail(path, line,
               "relative face index " + std::to_string(index) + " reaches before the first vertex (" +
                   std::to_string(defined) + " defined so far)");
        if (index > largest_index) {
          largest_index = index;
          largest_index_line = line;
        }
        if (++corners > static_cast<int>(kMaxPolygonVertices))
          fail(path, line, "face has more than " + std::to_string(kMaxPolygonVertices) +
                               " vertices (triangulating it would take minutes): split it");
      }
      if (corners < 3) fail(path, line, "face has fewer than 3 vertices");
      ++scan.faces;
    } else if (s.substr(0, 6) == "usemtl" && s.size() > 6 && (s[6] == ' ' || s[6] == '\t')) {
      const std::string name(trim(s.substr(7)));
      if (seen_materials.insert(name).second) scan.material_names.push_back(name);
    }
  });
  // Positive indices may refer forward (tinyobjloader allows it), so they are
  // checked against the final count.
  if (largest_index > static_cast<long long>(scan.vertices.size()))
    fail(path, largest_index_line,
         "face index " + std::to_string(largest_index) + " is out of range (the file has " +
             std::to_string(scan.vertices.size()) + " vertices)");
  return scan;
}

// Gives every `usemtl` name of the file a material id; ignores the file's own
// .mtl libraries, whose contents (colours, textures) attenuvis never uses.
class MaterialNames final : public tinyobj::MaterialReader {
 public:
  explicit MaterialNames(const std::vector<std::string>& names) : names_(names) {}
  bool operator()(const std::string& mat_id, std::vector<tinyobj::material_t>* materials,
                  std::map<std::string, int>* mat_map, std::string* /*warn*/,
                  std::string* /*err*/) override {
    if (mat_id != kMaterialSentinel) return true;
    for (const std::string& name : names_) {
      tinyobj::material_t m{};  // value-initialised: the struct has no constructor
      m.name = name;
      (*mat_map)[name] = static_cast<int>(materials->size());
      materials->push_back(m);
    }
    return true;
  }

 private:
  const std::vector<std::string>& names_;
};

std::string read_file(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) fail(path, 0, "is a directory, not an OBJ file");
  if (!std::filesystem::exists(path, ec)) fail(path, 0, "cannot open: " + (ec ? ec.message() : "no such file"));
  return io::read_input_file(path, kMaxSceneFileBytes);
}

}  // namespace

Mesh load_obj(const std::string& path) {
  const std::string text = read_file(path);
  Prescan scan = prescan(path, text);

  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warn, err;
  std::istringstream stream(std::string("mtllib ") + kMaterialSentinel + "\n" + text);
  MaterialNames reader(scan.material_names);
  if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, &stream, &reader,
                        /*triangulate=*/true, /*default_vcols_fallback=*/false))
    fail(path, 0, "tinyobjloader: " + std::string(trim(err)) + " (line numbers there count one extra line)");
  if (attrib.vertices.size() != 3 * scan.vertices.size())
    fail(path, 0, "internal error: vertex count disagrees with tinyobjloader");

  Mesh mesh;
  mesh.vertices = std::move(scan.vertices);
  const auto n_vertices = mesh.vertices.size();
  for (const tinyobj::shape_t& shape : shapes) {
    const std::string shape_name(trim(shape.name));
    const auto& indices = shape.mesh.indices;
    for (std::size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
      if (shape.mesh.num_face_vertices[f] != 3) fail(path, 0, "internal error: face not triangulated");
      std::array<std::uint32_t, 3> tri{};
      for (int k = 0; k < 3; ++k) {
        const int v = indices[3 * f + k].vertex_index;
        if (v < 0 || static_cast<std::size_t>(v) >= n_vertices)
          fail(path, 0, "face index out of range after triangulation");
        tri[k] = static_cast<std::uint32_t>(v);
      }
      std::string name = shape_name;
      if (name.empty()) {
        const int m = f < shape.mesh.material_ids.size() ? shape.mesh.material_ids[f] : -1;
        name = (m >= 0 && static_cast<std::size_t>(m) < materials.size()) ? materials[m].name : "default";
      }
      mesh.triangles.push_back(tri);
      mesh.triangle_group.push_back(static_cast<std::uint32_t>(mesh.add_group(name)));
    }
  }
  if (mesh.triangles.empty())
    fail(path, 0, "empty mesh: no triangles (" + std::to_string(mesh.vertices.size()) + " vertices, " +
                      std::to_string(scan.faces) + " faces)");
  return mesh;
}

namespace {

void validate_for_writing(const Mesh& mesh, const std::string& path) {
  if (mesh.triangle_group.size() != mesh.triangles.size())
    fail(path, 0, "cannot write mesh: triangle_group size differs from triangle count");
  for (const auto& v : mesh.vertices)
    if (!v.allFinite()) fail(path, 0, "cannot write mesh: a vertex is not finite");
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (auto i : mesh.triangles[t])
      if (i >= mesh.vertices.size()) fail(path, 0, "cannot write mesh: triangle index out of range");
    if (mesh.triangle_group[t] >= mesh.groups.size())
      fail(path, 0, "cannot write mesh: triangle group index out of range");
  }
}

}  // namespace

void write_obj(const Mesh& mesh, const std::string& path) {
  validate_for_writing(mesh, path);
  std::string out;
  out.reserve(mesh.vertices.size() * 60 + mesh.triangles.size() * 24 + 256);
  out += "# written by attenuvis: ";
  out += std::to_string(mesh.vertices.size()) + " vertices, " + std::to_string(mesh.triangles.size()) +
         " triangles, " + std::to_string(mesh.groups.size()) + " groups\n";
  for (const auto& v : mesh.vertices) {
    // Shortest round-trip text: UTM coordinates come back bit for bit.
    out += "v " + io::shortest(v.x()) + ' ' + io::shortest(v.y()) + ' ' + io::shortest(v.z()) + '\n';
  }
  // One `g` block per group, in the order of mesh.groups.
  std::vector<std::vector<std::uint32_t>> by_group(mesh.groups.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    by_group[mesh.triangle_group[t]].push_back(static_cast<std::uint32_t>(t));
  for (std::size_t g = 0; g < mesh.groups.size(); ++g) {
    if (by_group[g].empty()) continue;
    out += "g " + (mesh.groups[g].empty() ? std::string("default") : mesh.groups[g]) + "\n";
    for (auto t : by_group[g]) {
      const auto& tri = mesh.triangles[t];
      out += "f " + std::to_string(tri[0] + 1) + ' ' + std::to_string(tri[1] + 1) + ' ' +
             std::to_string(tri[2] + 1) + '\n';
    }
  }

  io::write_file_atomically(path, out);  // its errors name the path
}

}  // namespace attenuvis::visgraph
