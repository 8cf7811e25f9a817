// glTF 2.0 (.gltf with its buffers, or binary .glb) into a Mesh, through
// Debian's tinygltf.  glTF is y-up, metres, right-handed with +z towards the
// viewer (glTF 2.0 spec, 3.4 "Coordinate System and Units"): vertices are
// turned to attenuvis's z-up frame as (x, y, z) -> (x, -z, y).  Node
// transforms (matrix or translation/rotation/scale) of the default scene are
// applied.  One group per node (its name, else its mesh's name, else
// "node N"); no classes, no CRS.  Not part of the public interface: users
// read glTF through load_scene_file (scene_file.hpp); the tests and the
// fuzzer call the reader directly.
#pragma once

#include <attenuvis/visgraph/mesh.hpp>

#include <string>

namespace attenuvis::visgraph {

// Throws std::runtime_error naming the file and, where one is to blame, the
// mesh and primitive (unsupported primitive mode, non-float positions, an
// index out of range) or tinygltf's own message.
Mesh load_gltf(const std::string& path);

// True if the first bytes are a glTF file: the binary magic "glTF" or a JSON
// object with an "asset" member.
bool looks_like_gltf(const std::string& head);

}  // namespace attenuvis::visgraph
