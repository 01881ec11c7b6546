#pragma once
// Surface files (STL ASCII and binary, OBJ, PLY) in and out, through assimp. Coordinates are taken
// as millimetres, unscaled; checkSurface (mesh/SurfaceCheck.hpp) is where wrong units, holes and
// the like are caught. Assimp stores single-precision floats, so coordinates round-trip to about
// 1e-7 relative (1e-5 mm at 100 mm).
#include <string>

#include "mesh/SurfaceMesh.hpp"

namespace orthosim {

// Reads .stl, .obj or .ply (by extension, any case). Vertices at the same position with the same
// texture coordinates are merged (STL stores none shared), polygons are triangulated, nothing else
// is changed: no hole filling, no reorientation, no removal of degenerate triangles. Texture
// coordinates are kept when every part of the file has them. Throws std::runtime_error naming the
// file and the defect: missing or empty file, truncated binary STL, unreadable content, non-finite
// coordinates, no triangles, line or point primitives.
SurfaceMesh importSurface(const std::string& path);

enum class SurfaceEncoding { Binary, Ascii };  // OBJ is always ASCII

// Writes .stl (facet normals, no texture coordinates), .obj or .ply (shared vertices, area-weighted
// vertex normals, texture coordinates when present), chosen by extension. Throws
// std::runtime_error naming the file when the mesh is invalid or the write fails.
void exportSurface(const SurfaceMesh& mesh, const std::string& path,
                   SurfaceEncoding encoding = SurfaceEncoding::Binary);
// The same with RGB vertex colours in [0, 1], one column per vertex: PLY (uchar red, green, blue,
// alpha; always ASCII, as assimp 5.2's binary PLY writer garbles colours) or OBJ ("v x y z r g b");
// STL has no vertex colours and is refused.
void exportSurface(const SurfaceMesh& mesh, const Eigen::Matrix3Xf& vertexColours, const std::string& path,
                   SurfaceEncoding encoding = SurfaceEncoding::Binary);

// The same file's bytes in memory (a download): `extension` is "stl", "obj" or "ply" (any case).
// Throws std::runtime_error for another extension or an invalid mesh.
std::string exportSurfaceBytes(const SurfaceMesh& mesh, const std::string& extension,
                               SurfaceEncoding encoding = SurfaceEncoding::Binary);

}  // namespace orthosim
