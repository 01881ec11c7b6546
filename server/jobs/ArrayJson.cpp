#include "jobs/ArrayJson.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

namespace orthosim::server {
using nlohmann::json;

namespace {

std::vector<double> readNumbers(const json& j, const std::string& where) {
  if (!j.is_array()) throw BadResultFile(where + ": must be an array of numbers");
  std::vector<double> out;
  out.reserve(j.size());
  for (size_t i = 0; i < j.size(); ++i) {
    if (!j[i].is_number()) throw BadResultFile(where + "/" + std::to_string(i) + ": must be a number");
    const double v = j[i].get<double>();
    if (!std::isfinite(v)) throw BadResultFile(where + "/" + std::to_string(i) + ": must be finite");
    out.push_back(v);
  }
  return out;
}

}  // namespace

const json& member(const json& j, const char* key, const std::string& where) {
  if (!j.is_object()) throw BadResultFile((where.empty() ? "/" : where) + ": must be an object");
  auto it = j.find(key);
  if (it == j.end()) throw BadResultFile(where + "/" + key + ": required field is missing");
  return *it;
}

json matrixJson(const Eigen::Matrix3Xd& m) { return json(std::vector<double>(m.data(), m.data() + m.size())); }

json vectorJson(const Eigen::VectorXd& v) { return json(std::vector<double>(v.data(), v.data() + v.size())); }

json surfaceJson(const SurfaceMesh& s) {
  return {{"vertices", matrixJson(s.vertices)},
          {"triangles", std::vector<int>(s.triangles.data(), s.triangles.data() + s.triangles.size())}};
}

json posesJson(const std::vector<RigidPose>& poses) {
  json out = json::array();
  for (const RigidPose& p : poses) {
    std::vector<double> r;
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) r.push_back(p.R(i, k));
    out.push_back({{"R", r}, {"b", {p.b.x(), p.b.y(), p.b.z()}}});
  }
  return out;
}

Eigen::Matrix3Xd readMatrix(const json& j, const std::string& where, long long columns) {
  const std::vector<double> v = readNumbers(j, where);
  if (v.size() % 3 != 0) throw BadResultFile(where + ": " + std::to_string(v.size()) + " numbers, not x y z triples");
  if (columns >= 0 && static_cast<long long>(v.size() / 3) != columns)
    throw BadResultFile(where + ": " + std::to_string(v.size() / 3) + " points, expected " + std::to_string(columns));
  Eigen::Matrix3Xd m(3, static_cast<Eigen::Index>(v.size() / 3));
  std::copy(v.begin(), v.end(), m.data());
  return m;
}

Eigen::VectorXd readVector(const json& j, const std::string& where, long long size) {
  const std::vector<double> v = readNumbers(j, where);
  if (size >= 0 && static_cast<long long>(v.size()) != size)
    throw BadResultFile(where + ": " + std::to_string(v.size()) + " numbers, expected " + std::to_string(size));
  Eigen::VectorXd out(static_cast<Eigen::Index>(v.size()));
  std::copy(v.begin(), v.end(), out.data());
  return out;
}

SurfaceMesh readSurface(const json& j, const std::string& where) {
  SurfaceMesh s;
  s.vertices = readMatrix(member(j, "vertices", where), where + "/vertices");
  const json& t = member(j, "triangles", where);
  if (!t.is_array() || t.size() % 3 != 0)
    throw BadResultFile(where + "/triangles: must be an array of vertex index triples");
  s.triangles.resize(3, static_cast<Eigen::Index>(t.size() / 3));
  for (size_t i = 0; i < t.size(); ++i) {
    if (!t[i].is_number_integer() || t[i].get<long long>() < 0 || t[i].get<long long>() >= s.vertices.cols())
      throw BadResultFile(where + "/triangles/" + std::to_string(i) + ": must be a vertex index below " +
                          std::to_string(s.vertices.cols()));
    s.triangles.data()[i] = t[i].get<int>();
  }
  return s;
}

std::vector<RigidPose> readPoses(const json& j, const std::string& where) {
  if (!j.is_array()) throw BadResultFile(where + ": must be an array of poses");
  std::vector<RigidPose> out;
  for (size_t i = 0; i < j.size(); ++i) {
    const std::string at = where + "/" + std::to_string(i);
    const std::vector<double> r = readNumbers(member(j[i], "R", at), at + "/R");
    const std::vector<double> b = readNumbers(member(j[i], "b", at), at + "/b");
    if (r.size() != 9) throw BadResultFile(at + "/R: must be 9 numbers (row-major rotation)");
    if (b.size() != 3) throw BadResultFile(at + "/b: must be 3 numbers");
    RigidPose p;
    for (int a = 0; a < 3; ++a)
      for (int k = 0; k < 3; ++k) p.R(a, k) = r[static_cast<size_t>(3 * a + k)];
    p.b = Eigen::Vector3d(b[0], b[1], b[2]);
    out.push_back(p);
  }
  return out;
}

json readResultJson(const std::filesystem::path& file, const std::string& what, const std::string& format) {
  const std::string name = file.string();
  std::ifstream in(file, std::ios::binary);
  if (!in) throw BadResultFile(name + ": " + what + " cannot be read");
  std::ostringstream s;
  s << in.rdbuf();
  json j;
  try {
    j = json::parse(s.str());
  } catch (const json::parse_error& e) {
    throw BadResultFile(name + ": not JSON (" + e.what() + ")");
  }
  const json* f = j.is_object() && j.contains("format") ? &j["format"] : nullptr;
  if (!f || !f->is_string() || f->get<std::string>() != format) throw BadResultFile(name + ": /format: not " + format);
  return j;
}

}  // namespace orthosim::server
