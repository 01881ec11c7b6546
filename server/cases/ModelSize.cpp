#include "cases/ModelSize.hpp"

namespace orthosim::server {
namespace {

constexpr std::size_t kDouble = sizeof(double);
constexpr std::size_t kIndex = sizeof(int);

std::size_t meshBytes(const TetMesh& mesh) {
  return static_cast<std::size_t>(mesh.numNodes()) * 3 * kDouble +
         static_cast<std::size_t>(mesh.numTets()) * 4 * kIndex;
}

std::size_t skinBytes(const SurfaceMesh& skin) {
  const auto vertices = static_cast<std::size_t>(skin.numVertices());
  return vertices * (3 + static_cast<std::size_t>(skin.uv.rows())) * kDouble +
         static_cast<std::size_t>(skin.numTriangles()) * 3 * kIndex;
}

// Per embedded point: its tetrahedron, four nodes, four weights, the distance outside and an offset;
// per tetrahedron: its nodes, rest inverse and volume.
std::size_t embeddingBytes(std::size_t points, std::size_t tets) {
  return points * (5 * kIndex + 8 * kDouble) + tets * (4 * kIndex + 10 * kDouble);
}

}  // namespace

std::size_t estimatedBytes(const CaseModel& model) {
  const std::size_t skinVertices = static_cast<std::size_t>(model.tissue.skin.numVertices());
  return meshBytes(model.tissue.mesh) + meshBytes(model.scene.mesh) + skinBytes(model.tissue.skin) +
         embeddingBytes(skinVertices, static_cast<std::size_t>(model.scene.mesh.numTets()));
}

std::size_t estimatedBytes(const Model& model) {
  const auto tets = static_cast<std::size_t>(model.scene().mesh.numTets());
  // Tissue energy: rest inverse (3x3) and volume per element; scatter pattern: 144 value indices
  // per element (its 12x12 Hessian block).
  const std::size_t energy = tets * 10 * kDouble;
  const std::size_t pattern = tets * 144 * kIndex;
  const auto matrix = static_cast<std::size_t>(model.system().matrix().nonZeros()) * (kDouble + kIndex);
  const std::size_t restFactor = model.restFactor().entries() * kDouble;
  return meshBytes(model.scene().mesh) + energy + pattern + matrix + restFactor;
}

}  // namespace orthosim::server
