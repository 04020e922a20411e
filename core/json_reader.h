// Strict reading of our own JSON files: typed getters with defaults that remember which keys
// were read, so finish() can reject unknown keys (a typo must not silently fall back to a
// default). Every message names the file and the JSON path.
#pragma once

#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/math.h"

namespace dv {

using Json = nlohmann::json;

class JsonReader {
 public:
  // `where` is "file.json: /objects/2/material", used as the prefix of every error.
  JsonReader(const Json& object, std::string file, std::string path);

  const std::string& file() const { return file_; }
  const std::string& path() const { return path_; }
  std::string where() const;  // "file: path"
  std::string where(const std::string& key) const;

  bool has(const std::string& key) const;
  const Json& raw(const std::string& key);  // marks key as read; throws if missing

  double number(const std::string& key);
  double number(const std::string& key, double fallback);
  int integer(const std::string& key);
  int integer(const std::string& key, int fallback);
  bool boolean(const std::string& key, bool fallback);
  std::string string(const std::string& key);
  std::string string(const std::string& key, const std::string& fallback);
  dvec3 vec3(const std::string& key);
  dvec3 vec3(const std::string& key, const dvec3& fallback);
  ivec3 ivec3_value(const std::string& key);

  JsonReader child(const std::string& key);                  // key must hold an object
  std::vector<JsonReader> children(const std::string& key);  // key must hold an array of objects

  // Throws InputError listing keys present but never read.
  void finish() const;

  [[noreturn]] void fail(const std::string& key, const std::string& problem) const;

 private:
  const Json& object_;
  std::string file_;
  std::string path_;
  mutable std::set<std::string> read_;
};

// Parses JSON text read from `path`: errors (syntax, numbers out of range, a key given twice in
// one object) are InputErrors naming the file and the line/column of a syntax error.
Json parse_json_text(const std::string& text, const std::string& path);
// Reads a file and parses it with parse_json_text.
Json parse_json_file(const std::string& path);

}  // namespace dv
