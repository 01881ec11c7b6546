#pragma once
// A triangle surface (units: mm): skin, bone or tooth as clinicians hand it to us, before
// tetrahedralisation. Triangles run counter-clockwise seen from outside (right-hand normal points
// out), so a closed surface has positive signed volume.
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace orthosim {

struct SurfaceMesh {
  Eigen::Matrix3Xd vertices;   // 3 x numVertices positions
  Eigen::Matrix3Xi triangles;  // 3 x numTriangles vertex indices, 0-based
  Eigen::Matrix2Xd uv;         // 2 x numVertices texture coordinates, or empty (0 columns)

  int numVertices() const { return static_cast<int>(vertices.cols()); }
  int numTriangles() const { return static_cast<int>(triangles.cols()); }
  bool hasUv() const { return uv.cols() > 0; }

  // (b - a) x (c - a) of triangle t: its normal scaled by twice its area.
  Eigen::Vector3d areaVector(int t) const;
  double area() const;
  // Box around the vertices used by triangles (unused vertices do not count); empty when there
  // are no triangles.
  Eigen::AlignedBox3d boundingBox() const;
  // Volume enclosed by the triangles (divergence theorem): positive for a closed, outward surface;
  // for an open surface it depends on the origin and means nothing.
  double signedVolume() const;
  // Area-weighted vertex normals (unit length; zero for unused vertices), for export and display.
  Eigen::Matrix3Xd vertexNormals() const;
};

}  // namespace orthosim
