// Strict JSON reading for scene files and generator parameters (see json_reader.h).
#include "core/json_reader.h"

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <vector>

#include "core/error.h"

namespace dv {

JsonReader::JsonReader(const Json& object, std::string file, std::string path)
    : object_(object), file_(std::move(file)), path_(std::move(path)) {
  if (!object_.is_object()) throw InputError(where(), "expected a JSON object");
}

std::string JsonReader::where() const {
  return file_ + ": " + (path_.empty() ? "/" : path_);
}
std::string JsonReader::where(const std::string& key) const {
  return file_ + ": " + path_ + "/" + key;
}

bool JsonReader::has(const std::string& key) const {
  return object_.contains(key);
}

void JsonReader::fail(const std::string& key, const std::string& problem) const {
  throw InputError(key.empty() ? where() : where(key), problem);
}

const Json& JsonReader::raw(const std::string& key) {
  if (!has(key)) fail(key, "required key is missing");
  read_.insert(key);
  return object_.at(key);
}

static double finite_number(const JsonReader& r, const std::string& key, const Json& v) {
  if (!v.is_number()) r.fail(key, "expected a number, got " + std::string(v.type_name()));
  double d = v.get<double>();
  if (!std::isfinite(d)) r.fail(key, "number is not finite");
  return d;
}

double JsonReader::number(const std::string& key) {
  return finite_number(*this, key, raw(key));
}
double JsonReader::number(const std::string& key, double fallback) {
  return has(key) ? number(key) : fallback;
}

int JsonReader::integer(const std::string& key) {
  const Json& v = raw(key);
  if (!v.is_number_integer()) fail(key, "expected an integer");
  return v.get<int>();
}
int JsonReader::integer(const std::string& key, int fallback) {
  return has(key) ? integer(key) : fallback;
}

bool JsonReader::boolean(const std::string& key, bool fallback) {
  if (!has(key)) return fallback;
  const Json& v = raw(key);
  if (!v.is_boolean()) fail(key, "expected true or false");
  return v.get<bool>();
}

std::string JsonReader::string(const std::string& key) {
  const Json& v = raw(key);
  if (!v.is_string()) fail(key, "expected a string");
  return v.get<std::string>();
}
std::string JsonReader::string(const std::string& key, const std::string& fallback) {
  return has(key) ? string(key) : fallback;
}

dvec3 JsonReader::vec3(const std::string& key) {
  const Json& v = raw(key);
  if (!v.is_array() || v.size() != 3) fail(key, "expected an array of 3 numbers");
  dvec3 out;
  for (int i = 0; i < 3; ++i) out[i] = finite_number(*this, key, v[i]);
  return out;
}
dvec3 JsonReader::vec3(const std::string& key, const dvec3& fallback) {
  return has(key) ? vec3(key) : fallback;
}

ivec3 JsonReader::ivec3_value(const std::string& key) {
  const Json& v = raw(key);
  if (!v.is_array() || v.size() != 3) fail(key, "expected an array of 3 integers");
  ivec3 out;
  for (int i = 0; i < 3; ++i) {
    if (!v[i].is_number_integer()) fail(key, "expected an array of 3 integers");
    out[i] = v[i].get<int>();
  }
  return out;
}

JsonReader JsonReader::child(const std::string& key) {
  const Json& v = raw(key);
  if (!v.is_object()) fail(key, "expected a JSON object");
  return JsonReader(v, file_, path_ + "/" + key);
}

std::vector<JsonReader> JsonReader::children(const std::string& key) {
  const Json& v = raw(key);
  if (!v.is_array()) fail(key, "expected an array");
  std::vector<JsonReader> out;
  for (size_t i = 0; i < v.size(); ++i) {
    if (!v[i].is_object()) fail(key + "/" + std::to_string(i), "expected a JSON object");
    out.emplace_back(v[i], file_, path_ + "/" + key + "/" + std::to_string(i));
  }
  return out;
}

void JsonReader::finish() const {
  std::string unknown;
  for (auto it = object_.begin(); it != object_.end(); ++it) {
    if (!read_.count(it.key())) unknown += (unknown.empty() ? "" : ", ") + ("'" + it.key() + "'");
  }
  if (!unknown.empty()) throw InputError(where(), "unknown key(s) " + unknown);
}

Json parse_json_text(const std::string& text, const std::string& path) {
  // The keys seen in each object being parsed: a key given twice is an error (the parser would
  // keep the last one silently, like a typo falling back to a default).
  std::vector<std::set<std::string>> open_objects;
  const Json::parser_callback_t reject_duplicate_keys = [&](int, Json::parse_event_t event,
                                                            Json& parsed) {
    if (event == Json::parse_event_t::object_start) open_objects.emplace_back();
    if (event == Json::parse_event_t::object_end) open_objects.pop_back();
    if (event == Json::parse_event_t::key && !open_objects.back().insert(parsed).second)
      throw InputError(path, "malformed JSON: key " + parsed.dump() + " given twice in one object");
    return true;
  };
  try {
    return Json::parse(text, reject_duplicate_keys);
  } catch (const Json::exception& e) {  // syntax errors, numbers out of range
    throw InputError(path, std::string("malformed JSON: ") + e.what());
  }
}

Json parse_json_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "cannot open file");
  std::stringstream text;
  text << in.rdbuf();
  return parse_json_text(text.str(), path);
}

}  // namespace dv
