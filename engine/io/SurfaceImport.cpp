#include "io/SurfaceImport.hpp"

#include "io/CheckedFileSystem.hpp"
#include "io/PlyHeader.hpp"

#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <array>
#include <assimp/Exporter.hpp>
#include <assimp/Importer.hpp>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace orthosim {
namespace {

enum class Format { Stl, Obj, Ply };

Format formatOf(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".stl") return Format::Stl;
  if (ext == ".obj") return Format::Obj;
  if (ext == ".ply") return Format::Ply;
  throw std::runtime_error(path + ": unsupported surface format '" + ext + "': expected .stl, .obj or .ply");
}

std::string point(const Eigen::Vector3d& p) {
  std::ostringstream s;
  s << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return s.str();
}

// Assimp answers a truncated binary STL with "Failed to determine STL storage representation";
// say what is wrong instead. Mirrors assimp's own test: binary when the size is exactly
// 84 + 50 * (triangle count in the header), else ASCII when it starts with "solid" in plain text.
void checkStlStructure(const std::string& path, std::uintmax_t size) {
  std::ifstream in(path, std::ios::binary);
  std::array<char, 512> head{};
  in.read(head.data(), head.size());
  const std::size_t got = static_cast<std::size_t>(in.gcount());
  if (size >= 84) {
    std::uint32_t count = 0;
    std::memcpy(&count, head.data() + 80, sizeof count);
    if (84 + 50 * std::uint64_t(count) == size) return;
  }
  std::size_t i = 0;
  while (i < got && std::isspace(static_cast<unsigned char>(head[i]))) ++i;
  bool ascii = got >= i + 5 && std::strncmp(head.data() + i, "solid", 5) == 0;
  for (std::size_t k = 0; ascii && k < got; ++k) ascii = static_cast<unsigned char>(head[k]) < 128;
  if (ascii) {
    // Assimp reads a cut ASCII STL up to the last whole facet without complaint: the missing
    // facets would pass for a hole, or for the crop of a bone.
    in.clear();
    in.seekg(size > 512 ? static_cast<std::streamoff>(size - 512) : 0);
    const std::string tail((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (tail.find("endsolid") == std::string::npos)
      throw std::runtime_error(path + ": truncated ASCII STL: no 'endsolid' at the end");
    return;
  }
  if (size < 84)
    throw std::runtime_error(path + ": truncated binary STL: " + std::to_string(size) +
                             " bytes, shorter than the 84-byte header");
  std::uint32_t count = 0;
  std::memcpy(&count, head.data() + 80, sizeof count);
  const std::uint64_t expected = 84 + 50 * std::uint64_t(count);
  throw std::runtime_error(path + (size < expected ? ": truncated binary STL: " : ": binary STL of the wrong size: ") +
                           "the header announces " + std::to_string(count) + " triangles (" + std::to_string(expected) +
                           " bytes), the file has " + std::to_string(size) + " bytes");
}

// Exact (position, uv) key for merging vertices across the parts of a file.
using VertexKey = std::array<double, 5>;

}  // namespace

SurfaceMesh importSurface(const std::string& path) {
  const Format format = formatOf(path);
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw std::runtime_error(path + ": cannot open file");
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) throw std::runtime_error(path + ": cannot open file");
  if (size == 0) throw std::runtime_error(path + ": file is empty");
  if (format == Format::Stl) checkStlStructure(path, size);
  if (format == Format::Ply) checkPlySize(path, size);  // before assimp allocates what the header declares

  Assimp::Importer importer;
  // STL stores a normal per facet, so its corners differ in normal and would not be merged; normals
  // and colours are not needed, texture coordinates are.
  importer.SetPropertyInteger(AI_CONFIG_PP_RVC_FLAGS,
                              aiComponent_NORMALS | aiComponent_TANGENTS_AND_BITANGENTS | aiComponent_COLORS);
  const aiScene* scene = importer.ReadFile(path, aiProcess_RemoveComponent | aiProcess_Triangulate);
  if (!scene) throw std::runtime_error(path + ": cannot read: " + importer.GetErrorString());

  // Before merging: assimp's merge compares positions numerically and would fold a NaN vertex
  // into a neighbour, hiding the defect.
  // Counted per triangle: the importers store a vertex per triangle corner at this stage.
  long nonFinite = 0, badTriangles = 0, primitives = 0, triangles = 0;
  Eigen::Vector3d firstBad = Eigen::Vector3d::Zero();
  bool allUv = scene->mNumMeshes > 0;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    const bool uv = mesh->HasTextureCoords(0) && mesh->mNumUVComponents[0] >= 2;
    allUv = allUv && uv;
    std::vector<char> bad(mesh->mNumVertices, 0);
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D& p = mesh->mVertices[v];
      bool finite = std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
      if (uv)
        finite = finite && std::isfinite(mesh->mTextureCoords[0][v].x) && std::isfinite(mesh->mTextureCoords[0][v].y);
      if (!finite && nonFinite++ == 0) firstBad = Eigen::Vector3d(p.x, p.y, p.z);
      bad[v] = !finite;
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      (face.mNumIndices == 3 ? triangles : primitives)++;
      bool anyBad = false;
      for (unsigned k = 0; k < face.mNumIndices; ++k) anyBad = anyBad || bad[face.mIndices[k]];
      badTriangles += anyBad;
    }
  }
  if (nonFinite > 0)
    throw std::runtime_error(
        path + ": non-finite coordinates (NaN or infinite) " +
        (badTriangles > 0 ? "in " + std::to_string(badTriangles) + (badTriangles == 1 ? " triangle" : " triangles")
                          : std::string("at a vertex used by no triangle")) +
        ", e.g. " + point(firstBad));
  if (primitives > 0)
    throw std::runtime_error(path + ": " + std::to_string(primitives) +
                             (primitives == 1 ? " line or point primitive" : " line or point primitives") +
                             ": expected a triangle surface");
  if (triangles == 0) throw std::runtime_error(path + ": no triangles");

  scene = importer.ApplyPostProcessing(aiProcess_JoinIdenticalVertices);
  if (!scene) throw std::runtime_error(path + ": cannot read: " + importer.GetErrorString());

  // STL, OBJ and PLY carry no transforms: every part is used as stored. Parts (OBJ groups) share
  // their border vertices, merged here as assimp merges them within a part.
  SurfaceMesh out;
  std::map<VertexKey, int> index;
  std::vector<VertexKey> verts;
  std::vector<Eigen::Vector3i> tris;
  tris.reserve(triangles);
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    std::vector<int> local(mesh->mNumVertices);
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D& p = mesh->mVertices[v];
      VertexKey key{p.x, p.y, p.z, 0.0, 0.0};
      if (allUv) key[3] = mesh->mTextureCoords[0][v].x, key[4] = mesh->mTextureCoords[0][v].y;
      const auto [it, added] = index.emplace(key, static_cast<int>(verts.size()));
      if (added) verts.push_back(key);
      local[v] = it->second;
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const unsigned* i = mesh->mFaces[f].mIndices;
      tris.emplace_back(local[i[0]], local[i[1]], local[i[2]]);
    }
  }
  out.vertices.resize(3, static_cast<Eigen::Index>(verts.size()));
  if (allUv) out.uv.resize(2, static_cast<Eigen::Index>(verts.size()));
  for (std::size_t v = 0; v < verts.size(); ++v) {
    out.vertices.col(v) << verts[v][0], verts[v][1], verts[v][2];
    if (allUv) out.uv.col(v) << verts[v][3], verts[v][4];
  }
  out.triangles.resize(3, static_cast<Eigen::Index>(tris.size()));
  for (std::size_t t = 0; t < tris.size(); ++t) out.triangles.col(t) = tris[t];
  return out;
}

namespace {

// Assimp 5.2's binary PLY writer declares uchar colours but writes them as floats, a file no reader
// can parse: coloured PLY is written as ASCII.
const char* exporterId(Format format, SurfaceEncoding encoding, bool coloured = false) {
  const bool binary = encoding == SurfaceEncoding::Binary && !coloured;
  return format == Format::Stl   ? (binary ? "stlb" : "stl")
         : format == Format::Ply ? (binary ? "plyb" : "ply")
                                 : "objnomtl";  // no .mtl beside it
}

// The mesh as an assimp scene for `format`, with RGB vertex colours when `colours` is given; `path`
// names the target in errors.
std::unique_ptr<aiScene> exportScene(const SurfaceMesh& mesh, Format format, const std::string& path,
                                     const Eigen::Matrix3Xf* colours = nullptr) {
  if (mesh.numTriangles() == 0) throw std::runtime_error(path + ": cannot export: no triangles");
  if (mesh.hasUv() && mesh.uv.cols() != mesh.vertices.cols())
    throw std::runtime_error(path + ": cannot export: " + std::to_string(mesh.uv.cols()) + " texture coordinates for " +
                             std::to_string(mesh.numVertices()) + " vertices");
  for (int t = 0; t < mesh.numTriangles(); ++t)
    for (int k = 0; k < 3; ++k)
      if (mesh.triangles(k, t) < 0 || mesh.triangles(k, t) >= mesh.numVertices())
        throw std::runtime_error(path + ": cannot export: triangle " + std::to_string(t) + " refers to vertex " +
                                 std::to_string(mesh.triangles(k, t)) + " of " + std::to_string(mesh.numVertices()));
  if (colours && format == Format::Stl)
    throw std::runtime_error(path + ": cannot export vertex colours to STL (use .ply or .obj)");
  if (colours && colours->cols() != mesh.vertices.cols())
    throw std::runtime_error(path + ": cannot export: " + std::to_string(colours->cols()) + " colours for " +
                             std::to_string(mesh.numVertices()) + " vertices");

  auto scene = std::make_unique<aiScene>();  // owns everything below
  scene->mRootNode = new aiNode();
  scene->mRootNode->mNumMeshes = 1;
  scene->mRootNode->mMeshes = new unsigned[1]{0};
  scene->mNumMaterials = 1;
  scene->mMaterials = new aiMaterial* [1] { new aiMaterial() };
  scene->mNumMeshes = 1;
  scene->mMeshes = new aiMesh* [1] { new aiMesh() };
  aiMesh& am = *scene->mMeshes[0];
  am.mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
  const unsigned nt = static_cast<unsigned>(mesh.numTriangles());
  am.mNumFaces = nt;
  am.mFaces = new aiFace[nt];
  auto vec = [](const Eigen::Vector3d& p) { return aiVector3D(ai_real(p.x()), ai_real(p.y()), ai_real(p.z())); };

  if (format == Format::Stl) {
    // Assimp's STL writer averages the corners' normals into the facet normal, so each facet gets
    // its own corners carrying its own normal.
    am.mNumVertices = 3 * nt;
    am.mVertices = new aiVector3D[3 * nt];
    am.mNormals = new aiVector3D[3 * nt];
    for (unsigned t = 0; t < nt; ++t) {
      const Eigen::Vector3d w = mesh.areaVector(static_cast<int>(t));
      const Eigen::Vector3d n = w.norm() > 0 ? Eigen::Vector3d(w.normalized()) : Eigen::Vector3d::Zero();
      am.mFaces[t].mNumIndices = 3;
      am.mFaces[t].mIndices = new unsigned[3];
      for (unsigned k = 0; k < 3; ++k) {
        am.mVertices[3 * t + k] = vec(mesh.vertices.col(mesh.triangles(k, t)));
        am.mNormals[3 * t + k] = vec(n);
        am.mFaces[t].mIndices[k] = 3 * t + k;
      }
    }
  } else {
    // Our own normals, else assimp's OBJ writer generates them and gets them wrong on shared vertices.
    const unsigned nv = static_cast<unsigned>(mesh.numVertices());
    const Eigen::Matrix3Xd normals = mesh.vertexNormals();
    am.mNumVertices = nv;
    am.mVertices = new aiVector3D[nv];
    am.mNormals = new aiVector3D[nv];
    for (unsigned v = 0; v < nv; ++v) {
      am.mVertices[v] = vec(mesh.vertices.col(v));
      am.mNormals[v] = vec(normals.col(v));
    }
    if (mesh.hasUv()) {
      am.mTextureCoords[0] = new aiVector3D[nv];
      am.mNumUVComponents[0] = 2;
      for (unsigned v = 0; v < nv; ++v)
        am.mTextureCoords[0][v] = aiVector3D(ai_real(mesh.uv(0, v)), ai_real(mesh.uv(1, v)), 0);
    }
    if (colours) {
      am.mColors[0] = new aiColor4D[nv];
      for (unsigned v = 0; v < nv; ++v) {
        const Eigen::Vector3f c = colours->col(v).cwiseMax(0.0f).cwiseMin(1.0f);
        am.mColors[0][v] = aiColor4D(c.x(), c.y(), c.z(), 1.0f);
      }
    }
    for (unsigned t = 0; t < nt; ++t) {
      am.mFaces[t].mNumIndices = 3;
      am.mFaces[t].mIndices = new unsigned[3];
      for (unsigned k = 0; k < 3; ++k) am.mFaces[t].mIndices[k] = static_cast<unsigned>(mesh.triangles(k, t));
    }
  }

  return scene;
}

}  // namespace

namespace {

// Writes through a CheckedFileSystem: a full disk is an error naming the file and the reason.
void writeScene(const aiScene& scene, const std::string& formatId, const std::string& path) {
  auto failure = std::make_shared<std::string>();
  Assimp::Exporter exporter;
  exporter.SetIOHandler(new CheckedFileSystem(failure));  // the exporter owns it
  const aiReturn result = exporter.Export(&scene, formatId, path);
  if (!failure->empty()) throw std::runtime_error("cannot write " + *failure);
  if (result != AI_SUCCESS) throw std::runtime_error(path + ": cannot write: " + exporter.GetErrorString());
}

}  // namespace

void exportSurface(const SurfaceMesh& mesh, const std::string& path, SurfaceEncoding encoding) {
  const Format format = formatOf(path);
  writeScene(*exportScene(mesh, format, path), exporterId(format, encoding), path);
}

void exportSurface(const SurfaceMesh& mesh, const Eigen::Matrix3Xf& vertexColours, const std::string& path,
                   SurfaceEncoding encoding) {
  const Format format = formatOf(path);
  writeScene(*exportScene(mesh, format, path, &vertexColours), exporterId(format, encoding, true), path);
}

std::string exportSurfaceBytes(const SurfaceMesh& mesh, const std::string& extension, SurfaceEncoding encoding) {
  const std::string name = "surface." + extension;
  const Format format = formatOf(name);
  const std::unique_ptr<aiScene> scene = exportScene(mesh, format, name);
  Assimp::Exporter exporter;
  const aiExportDataBlob* blob = exporter.ExportToBlob(scene.get(), exporterId(format, encoding));
  if (!blob) throw std::runtime_error(name + ": cannot export: " + exporter.GetErrorString());
  return std::string(static_cast<const char*>(blob->data), blob->size);
}

}  // namespace orthosim
