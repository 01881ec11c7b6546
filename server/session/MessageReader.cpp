#include "session/MessageReader.hpp"

#include <cmath>
#include <sstream>

namespace orthosim::server {

std::string jsonPointer(const std::string& parent, const std::string& key) {
  std::string out = parent + "/";
  for (const char c : key) {
    if (c == '~')
      out += "~0";
    else if (c == '/')
      out += "~1";
    else
      out += c;
  }
  return out;
}

namespace {

// A number as the client wrote it: 2^64-1 stays 18446744073709551615 (not -1), 0.1 stays 0.1.
std::string asSent(const nlohmann::json& v) { return v.dump(); }

}  // namespace

MessageReader::MessageReader(const nlohmann::json& j, std::string pointer) : j_(j), pointer_(std::move(pointer)) {
  if (!j_.is_object()) fail("bad_value", "must be a JSON object");
}

void MessageReader::fail(const std::string& code, const std::string& what, const std::string& field) const {
  const std::string where = field.empty() ? pointer_ : jsonPointer(pointer_, field);
  throw ProtocolError(code, (where.empty() ? std::string("message") : where) + ": " + what, where);
}

bool MessageReader::has(const std::string& k) {
  seen_.insert(k);
  return j_.contains(k) && !j_.at(k).is_null();
}

const nlohmann::json& MessageReader::field(const std::string& k) {
  if (!has(k)) fail("missing_field", "required field is missing", k);
  return j_.at(k);
}

std::string MessageReader::string(const std::string& k) {
  const nlohmann::json& v = field(k);
  if (!v.is_string()) fail("bad_value", "must be a string", k);
  return v.get<std::string>();
}

std::optional<std::string> MessageReader::optionalString(const std::string& k) {
  if (!has(k)) return std::nullopt;
  return string(k);
}

double MessageReader::number(const std::string& k, double dflt, double lo, double hi, const std::string& unit) {
  if (!has(k)) return dflt;
  const nlohmann::json& v = j_.at(k);
  if (!v.is_number()) fail("bad_value", "must be a number (" + unit + ")", k);
  const double x = v.get<double>();
  if (!std::isfinite(x)) fail("bad_value", "must be finite", k);
  if (x < lo || x > hi) {
    std::ostringstream s;
    s << asSent(v) << " " << unit << " is outside the allowed range [" << lo << ", " << hi << "] " << unit;
    fail("out_of_range", s.str(), k);
  }
  return x;
}

std::optional<long long> MessageReader::optionalInteger(const std::string& k, long long lo, long long hi) {
  if (!has(k)) return std::nullopt;
  const nlohmann::json& v = j_.at(k);
  if (!v.is_number_integer()) fail("bad_value", "must be an integer", k);
  // An unsigned value beyond long long is out of range too, not wrapped to a negative number.
  const bool beyond = v.is_number_unsigned() && v.get<unsigned long long>() > static_cast<unsigned long long>(hi);
  const long long x = beyond ? hi : v.get<long long>();
  if (beyond || x < lo || x > hi)
    fail("out_of_range", asSent(v) + " is outside [" + std::to_string(lo) + ", " + std::to_string(hi) + "]", k);
  return x;
}

bool MessageReader::boolean(const std::string& k, bool dflt) {
  if (!has(k)) return dflt;
  if (!j_.at(k).is_boolean()) fail("bad_value", "must be true or false", k);
  return j_.at(k).get<bool>();
}

MessageReader MessageReader::object(const std::string& k) { return MessageReader(field(k), pointer(k)); }

void MessageReader::rejectUnknown() const {
  for (const auto& item : j_.items())
    if (!seen_.count(item.key())) fail("unknown_field", "unknown field", item.key());
}

}  // namespace orthosim::server
