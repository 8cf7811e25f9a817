// Wavefront OBJ in and out.  Naming rule: a triangle's group is its OBJ group
// (`g`, or `o` where the file uses objects); a triangle with no group takes
// its material name (`usemtl`); one with neither is in group "default".
#pragma once

#include <attenuvis/visgraph/mesh.hpp>

#include <string>

namespace attenuvis::visgraph {

// Reads an OBJ file; polygons are triangulated, groups and materials kept.
// Throws std::runtime_error naming the file (and line, where one is to blame)
// for an unreadable file, NaN/inf vertices, bad indices or an empty mesh.
Mesh load_obj(const std::string& path);

// Writes the mesh as OBJ, one `g` block per group, atomically (all or
// nothing: attenuvis::io staged file).
void write_obj(const Mesh& mesh, const std::string& path);

}  // namespace attenuvis::visgraph
