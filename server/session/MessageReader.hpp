#pragma once
// Reads the fields of one JSON object of a client message. Every refusal is a ProtocolError that
// names the field by its JSON pointer; fields nobody asked about are refused (a typo such as
// "anterior" for "anterior_mm" must not silently do nothing).
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>

#include "session/ProtocolError.hpp"

namespace orthosim::server {

// `parent` + "/" + `key` as a JSON pointer (RFC 6901): "~" and "/" in the key escaped as "~0", "~1".
std::string jsonPointer(const std::string& parent, const std::string& key);

class MessageReader {
 public:
  // Throws bad_value when `j` is not an object.
  MessageReader(const nlohmann::json& j, std::string pointer);

  // Throws ProtocolError at this object or at its field `field` (a key, not a pointer).
  [[noreturn]] void fail(const std::string& code, const std::string& what, const std::string& field = "") const;
  bool has(const std::string& k);
  std::string string(const std::string& k);
  std::optional<std::string> optionalString(const std::string& k);
  // A finite number in [lo, hi]; `unit` is named in the message ("mm", "degrees").
  double number(const std::string& k, double dflt, double lo, double hi, const std::string& unit);
  std::optional<long long> optionalInteger(const std::string& k, long long lo, long long hi);
  bool boolean(const std::string& k, bool dflt);
  MessageReader object(const std::string& k);
  const nlohmann::json& raw() const { return j_; }
  std::string pointer(const std::string& k) const { return jsonPointer(pointer_, k); }
  // Throws unknown_field naming the first field never asked about.
  void rejectUnknown() const;

 private:
  const nlohmann::json& field(const std::string& k);

  const nlohmann::json& j_;
  std::string pointer_;
  std::set<std::string> seen_;
};

}  // namespace orthosim::server
