#include "render/GpuMesh.hpp"

#include <map>
#include <string>
#include <tuple>

#include "render/GlCheck.hpp"
#include "render/RenderError.hpp"

namespace orthosim::render {
namespace {

void check(const SurfaceMesh& m, const std::string& what) {
  if (m.numTriangles() == 0 || m.numVertices() == 0)
    throw RenderError(what + ": empty mesh (" + std::to_string(m.numVertices()) + " vertices, " +
                      std::to_string(m.numTriangles()) + " triangles)");
  if (m.triangles.minCoeff() < 0 || m.triangles.maxCoeff() >= m.numVertices())
    throw RenderError(what + ": a triangle's vertex index lies outside 0.." + std::to_string(m.numVertices() - 1));
  if (!m.vertices.allFinite()) throw RenderError(what + ": a vertex position is not finite");
  if (m.hasUv() && m.uv.cols() != m.vertices.cols())
    throw RenderError(what + ": " + std::to_string(m.uv.cols()) + " texture coordinates for " +
                      std::to_string(m.numVertices()) + " vertices");
}

// Vertices duplicated along a uv seam share one normal, so the seam does not show in the light.
std::vector<int> weldByPosition(const Eigen::Matrix3Xd& v) {
  std::map<std::tuple<double, double, double>, int> first;
  std::vector<int> weld(static_cast<size_t>(v.cols()));
  for (Eigen::Index i = 0; i < v.cols(); ++i)
    weld[static_cast<size_t>(i)] =
        first.emplace(std::make_tuple(v(0, i), v(1, i), v(2, i)), static_cast<int>(i)).first->second;
  return weld;
}

// Uploads `data` to a new buffer bound to vertex attribute `location` with `size` floats a vertex.
GlBuffer attributeBuffer(GLuint location, int size, const std::vector<float>& data, GLenum usage) {
  GlBuffer b = newBuffer();
  glBindBuffer(GL_ARRAY_BUFFER, b.get());
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(data.size() * sizeof(float)), data.data(), usage);
  glEnableVertexAttribArray(location);
  glVertexAttribPointer(location, size, GL_FLOAT, GL_FALSE, 0, nullptr);
  return b;
}

std::vector<float> toFloats(const Eigen::MatrixXd& m) {
  std::vector<float> f(static_cast<size_t>(m.size()));
  for (Eigen::Index i = 0; i < m.size(); ++i) f[static_cast<size_t>(i)] = static_cast<float>(m.data()[i]);
  return f;
}

// Position (attribute `p`) and normal (`p` + 1) interleaved in one buffer.
void pointInterleaved(GLuint p) {
  const GLsizei stride = 6 * sizeof(float);
  glEnableVertexAttribArray(p);
  glVertexAttribPointer(p, 3, GL_FLOAT, GL_FALSE, stride, nullptr);
  glEnableVertexAttribArray(p + 1);
  glVertexAttribPointer(p + 1, 3, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<const void*>(3 * sizeof(float)));
}

}  // namespace

GpuMesh::GpuMesh(const SurfaceMesh& rest, const std::string& what)
    : what_(what), triangles_(rest.triangles), positions_(rest.vertices), vao_(newVertexArray()) {
  check(rest, what);
  weld_ = weldByPosition(rest.vertices);
  fillNormals(rest.vertices);
  glBindVertexArray(vao_.get());
  const GLsizeiptr bytes = static_cast<GLsizeiptr>(interleaved_.size() * sizeof(float));
  for (GlBuffer* b : {&current_, &rest_}) {  // current (0, 1) starts at rest (2, 3)
    *b = newBuffer();
    glBindBuffer(GL_ARRAY_BUFFER, b->get());
    glBufferData(GL_ARRAY_BUFFER, bytes, interleaved_.data(), b == &current_ ? GL_DYNAMIC_DRAW : GL_STATIC_DRAW);
    pointInterleaved(b == &current_ ? 0 : 2);
  }
  if (rest.hasUv()) uv_ = attributeBuffer(4, 2, toFloats(rest.uv), GL_STATIC_DRAW);
  std::vector<float> scalars(static_cast<size_t>(2 * rest.numVertices()), 0.0f);  // (value, in map) a vertex
  for (size_t i = 1; i < scalars.size(); i += 2) scalars[i] = 1.0f;
  scalars_ = attributeBuffer(5, 2, scalars, GL_DYNAMIC_DRAW);
  indices_ = newBuffer();
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, indices_.get());
  const Eigen::Matrix<unsigned, 3, Eigen::Dynamic> idx = triangles_.cast<unsigned>();
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(idx.size() * sizeof(unsigned)), idx.data(),
               GL_STATIC_DRAW);
  glBindVertexArray(0);
  checkGl(what + ": uploading " + std::to_string(rest.numTriangles()) + " triangles");
}

void GpuMesh::fillNormals(const Eigen::Matrix3Xd& x) {
  Eigen::Matrix3Xd n = Eigen::Matrix3Xd::Zero(3, x.cols());
  for (Eigen::Index t = 0; t < triangles_.cols(); ++t) {
    const Eigen::Vector3d a = x.col(triangles_(0, t));
    const Eigen::Vector3d w = (x.col(triangles_(1, t)) - a).cross(x.col(triangles_(2, t)) - a);  // area-weighted
    for (int k = 0; k < 3; ++k) n.col(weld_[static_cast<size_t>(triangles_(k, t))]) += w;
  }
  interleaved_.resize(static_cast<size_t>(6 * x.cols()));
  for (Eigen::Index i = 0; i < x.cols(); ++i) {
    const Eigen::Vector3d ni = n.col(weld_[static_cast<size_t>(i)]).normalized();
    float* out = interleaved_.data() + 6 * i;
    for (int k = 0; k < 3; ++k) {
      out[k] = static_cast<float>(x(k, i));
      out[3 + k] = static_cast<float>(ni[k]);
    }
  }
}

void GpuMesh::updatePositions(const Eigen::Matrix3Xd& x) {
  if (x.cols() != numVertices())
    throw RenderError(what_ + ": " + std::to_string(x.cols()) + " new positions for " + std::to_string(numVertices()) +
                      " vertices (the topology is fixed once set)");
  if (!x.allFinite()) throw RenderError(what_ + ": a new vertex position is not finite");
  positions_ = x;
  fillNormals(x);
  glBindBuffer(GL_ARRAY_BUFFER, current_.get());
  glBufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(interleaved_.size() * sizeof(float)),
                  interleaved_.data());
  checkGl(what_ + ": updating positions");
}

void GpuMesh::updateScalars(const Eigen::VectorXd& values, const std::vector<char>& inMap) {
  if (values.size() != numVertices())
    throw RenderError(what_ + ": " + std::to_string(values.size()) + " colour-map values for " +
                      std::to_string(numVertices()) + " vertices");
  if (!inMap.empty() && inMap.size() != static_cast<size_t>(numVertices()))
    throw RenderError(what_ + ": " + std::to_string(inMap.size()) + " colour-map flags for " +
                      std::to_string(numVertices()) + " vertices");
  std::vector<float> f(static_cast<size_t>(2 * values.size()));
  for (Eigen::Index i = 0; i < values.size(); ++i) {
    f[static_cast<size_t>(2 * i)] = static_cast<float>(values[i]);
    f[static_cast<size_t>(2 * i + 1)] = inMap.empty() || inMap[static_cast<size_t>(i)] ? 1.0f : 0.0f;
  }
  glBindBuffer(GL_ARRAY_BUFFER, scalars_.get());
  glBufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(f.size() * sizeof(float)), f.data());
  checkGl(what_ + ": updating colour-map values");
}

void GpuMesh::draw() const {
  glBindVertexArray(vao_.get());
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(triangles_.size()), GL_UNSIGNED_INT, nullptr);
  glBindVertexArray(0);
}

}  // namespace orthosim::render
