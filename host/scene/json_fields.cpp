// json_fields.cpp: typed reads of scene-file JSON values (see json_fields.h).
#include "scene/json_fields.h"

#include <algorithm>
#include <cmath>

#include "scene/load_util.h"
#include "util/errors.h"

namespace montecl {

using nlohmann::json;

void jsonFail(const JsonCtx& ctx, const std::string& where, const std::string& problem) {
  loadFail(ctx.file, where, problem);
}

std::string childKey(const std::string& prefix, const std::string& key) {
  return prefix.empty() ? key : prefix + "." + key;
}

void warnUnknownKeys(const JsonCtx& ctx, const json& obj, const std::string& prefix,
                     std::initializer_list<const char*> known) {
  for (auto it = obj.begin(); it != obj.end(); ++it) {
    bool isKnown = std::any_of(known.begin(), known.end(), [&](const char* k) { return it.key() == k; });
    if (!isKnown)
      ctx.warnings.push_back(oneLine(ctx.file, 4096) + ": " + oneLine(childKey(prefix, it.key())) +
                             ": unknown key, ignored");
  }
}

const json& requireObject(const JsonCtx& ctx, const json& v, const std::string& where) {
  if (!v.is_object()) jsonFail(ctx, where, std::string("expected an object, got ") + v.type_name());
  return v;
}

const json& requireKey(const JsonCtx& ctx, const json& obj, const std::string& prefix, const char* key) {
  auto it = obj.find(key);
  if (it == obj.end()) jsonFail(ctx, childKey(prefix, key), "missing required key");
  return *it;
}

const json* optionalKey(const json& obj, const char* key) {
  auto it = obj.find(key);
  return it == obj.end() ? nullptr : &*it;
}

float getFloat(const JsonCtx& ctx, const json& v, const std::string& where) {
  if (!v.is_number()) jsonFail(ctx, where, std::string("expected a number, got ") + v.type_name());
  float f = v.get<float>();
  if (!std::isfinite(f)) jsonFail(ctx, where, "number out of float range");
  return f;
}

long long getInteger(const JsonCtx& ctx, const json& v, const std::string& where, long long lo, long long hi,
                     const char* expected) {
  if (!v.is_number()) jsonFail(ctx, where, std::string("expected ") + expected + ", got " + v.type_name());
  double d = v.get<double>();
  if (d != std::floor(d)) jsonFail(ctx, where, std::string("expected ") + expected + ", got " + v.dump());
  if (d < static_cast<double>(lo) || d > static_cast<double>(hi))
    jsonFail(ctx, where, std::string("expected ") + expected + ", got " + v.dump());
  return static_cast<long long>(d);
}

int getPositiveInt(const JsonCtx& ctx, const json& v, const std::string& where, int hi, const char* expected) {
  return static_cast<int>(getInteger(ctx, v, where, 1, hi, expected));
}

glm::vec3 getVec3(const JsonCtx& ctx, const json& v, const std::string& where) {
  if (!v.is_array() || v.size() != 3)
    jsonFail(ctx, where, std::string("expected an array of 3 numbers, got ") +
                             (v.is_array() ? "an array of " + std::to_string(v.size()) : std::string(v.type_name())));
  return glm::vec3(getFloat(ctx, v[0], where + "[0]"), getFloat(ctx, v[1], where + "[1]"),
                   getFloat(ctx, v[2], where + "[2]"));
}

glm::vec3 getColor(const JsonCtx& ctx, const json& v, const std::string& where) {
  glm::vec3 c = getVec3(ctx, v, where);
  if (c.x < 0 || c.y < 0 || c.z < 0) jsonFail(ctx, where, "components must be >= 0");
  return c;
}

bool getBool(const JsonCtx& ctx, const json& v, const std::string& where) {
  if (!v.is_boolean()) jsonFail(ctx, where, std::string("expected true or false, got ") + v.dump());
  return v.get<bool>();
}

std::string getString(const JsonCtx& ctx, const json& v, const std::string& where, const char* what) {
  if (!v.is_string()) jsonFail(ctx, where, std::string("expected ") + what + ", got " + v.type_name());
  if (v.get<std::string>().empty()) jsonFail(ctx, where, std::string("empty ") + what);
  return v.get<std::string>();
}

}  // namespace montecl
