#pragma once
// Wavefront OBJ input for the reference tracer, through Debian's tinyobjloader (only the
// examples depend on it, never the shade library).

#include <string>

#include "mesh.hpp"

namespace tracer {

/// The triangles of the Wavefront OBJ file at `path` as one mesh: every face is
/// triangulated (a polygon of n corners gives n - 2 triangles), each distinct pair of
/// (position, texture coordinate) indices becomes one vertex, and `uvs` holds one texture
/// coordinate per vertex when every face corner names one (else it is empty). Normals in
/// the file are ignored: each vertex normal is the normalised sum of cross(v1 - v0, v2 - v0)
/// over the triangles that use it (an area-weighted average of the face normals).
/// Throws std::runtime_error naming the file when it cannot be read, does not parse, has
/// no triangle, has a non-finite position or texture coordinate, has a face index outside
/// its vertex list, or has a vertex whose triangles are all degenerate.
[[nodiscard]] mesh load_obj(const std::string& path);

} // namespace tracer
