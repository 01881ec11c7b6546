#pragma once
// Reads the fields of one JSON object of a scene or case file, naming `file: path.to.field` in every
// error and refusing fields it was not asked about (a typo must not be silently ignored).
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>
#include <string>

namespace orthosim {

struct SceneError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class JsonReader {
 public:
  JsonReader(std::string file, const nlohmann::json& j, std::string path);

  [[noreturn]] void fail(const std::string& what, const std::string& field = "") const;
  bool has(const std::string& k);
  const nlohmann::json& get(const std::string& k);
  JsonReader child(const std::string& k) { return JsonReader(file_, get(k), sub(k)); }
  std::string sub(const std::string& k) const { return path_.empty() ? k : path_ + "." + k; }

  double number(const std::string& k);
  double number(const std::string& k, double dflt) { return has(k) ? number(k) : dflt; }
  int integer(const std::string& k, int dflt, int lo, int hi);
  bool boolean(const std::string& k, bool dflt);
  std::string string(const std::string& k);
  Eigen::Vector3d vector3(const std::string& k, const Eigen::Vector3d& dflt);
  Eigen::Vector3d vector3(const std::string& k);
  // Each element of an array field, as a reader named "field[i]"; the field must be an array.
  template <class F>
  void forEach(const std::string& k, F&& f) {
    const nlohmann::json& arr = get(k);
    if (!arr.is_array()) fail("must be an array", k);
    for (size_t i = 0; i < arr.size(); ++i) f(JsonReader(file_, arr[i], sub(k) + "[" + std::to_string(i) + "]"));
  }
  // Throws naming the first field that was never asked about.
  void rejectUnknown() const;
  const nlohmann::json& raw() const { return j_; }
  const std::string& file() const { return file_; }
  const std::string& path() const { return path_; }

 private:
  std::string file_;
  const nlohmann::json& j_;
  std::string path_;
  std::set<std::string> seen_;
};

}  // namespace orthosim
