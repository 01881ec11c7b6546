#pragma once
// Matrices and surfaces in the JSON result files workers leave in the data folder (band and
// cohort jobs): flat arrays of numbers, doubles printed to round-trip exactly. The readers check
// every element and name what is wrong and where (a JSON pointer), never return NaN.
#include <Eigen/Core>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "mesh/SurfaceMesh.hpp"
#include "scene/RigidPose.hpp"

namespace orthosim::server {

// A result file that is not what it says: the file (or message), what is wrong and where.
class BadResultFile : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

nlohmann::json matrixJson(const Eigen::Matrix3Xd& m);  // [x0, y0, z0, x1, ...]
nlohmann::json vectorJson(const Eigen::VectorXd& v);
nlohmann::json surfaceJson(const SurfaceMesh& s);               // {"vertices": [...], "triangles": [...]}
nlohmann::json posesJson(const std::vector<RigidPose>& poses);  // [{"R": [9, row-major], "b": [3]}, ...]

// `columns` < 0: any count (a multiple of 3 numbers). Throws BadResultFile "WHERE: reason".
Eigen::Matrix3Xd readMatrix(const nlohmann::json& j, const std::string& where, long long columns = -1);
Eigen::VectorXd readVector(const nlohmann::json& j, const std::string& where, long long size = -1);
// Triangles index the vertices they come with.
SurfaceMesh readSurface(const nlohmann::json& j, const std::string& where);
std::vector<RigidPose> readPoses(const nlohmann::json& j, const std::string& where);

// The JSON of result file `file` whose "format" must be `format`; `what` ("the band job's result")
// names it when it cannot be read. Throws BadResultFile "FILE: reason" otherwise.
nlohmann::json readResultJson(const std::filesystem::path& file, const std::string& what, const std::string& format);

// The member `key` of object `j`, or BadResultFile "WHERE/KEY: required field is missing".
const nlohmann::json& member(const nlohmann::json& j, const char* key, const std::string& where);

}  // namespace orthosim::server
