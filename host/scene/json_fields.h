// json_fields.h: typed reads of scene-file JSON values with one-line InputErrors
// "<file>: <key path>: <problem>", and unknown keys as warnings. Used by scene_file.cpp and
// mesh_entry.cpp.
#pragma once
#include <nlohmann/json.hpp>

#include <glm/glm.hpp>
#include <initializer_list>
#include <string>
#include <vector>

#include "scene/render_choices.h"

namespace montecl {

// The scene file being read, for messages and warnings.
struct JsonCtx {
  std::string file;
  std::vector<std::string>& warnings;
};

[[noreturn]] void jsonFail(const JsonCtx& ctx, const std::string& where, const std::string& problem);
std::string childKey(const std::string& prefix, const std::string& key);  // "a.b"

void warnUnknownKeys(const JsonCtx& ctx, const nlohmann::json& obj, const std::string& prefix,
                     std::initializer_list<const char*> known);
const nlohmann::json& requireObject(const JsonCtx& ctx, const nlohmann::json& v, const std::string& where);
const nlohmann::json& requireKey(const JsonCtx& ctx, const nlohmann::json& obj, const std::string& prefix,
                                 const char* key);
const nlohmann::json* optionalKey(const nlohmann::json& obj, const char* key);

float getFloat(const JsonCtx& ctx, const nlohmann::json& v, const std::string& where);
// An integer in [lo, hi] (integral floats like 512.0 are accepted).
long long getInteger(const JsonCtx& ctx, const nlohmann::json& v, const std::string& where, long long lo,
                     long long hi, const char* expected);
int getPositiveInt(const JsonCtx& ctx, const nlohmann::json& v, const std::string& where, int hi,
                   const char* expected = "a positive integer");
glm::vec3 getVec3(const JsonCtx& ctx, const nlohmann::json& v, const std::string& where);
glm::vec3 getColor(const JsonCtx& ctx, const nlohmann::json& v, const std::string& where);  // >= 0
bool getBool(const JsonCtx& ctx, const nlohmann::json& v, const std::string& where);
std::string getString(const JsonCtx& ctx, const nlohmann::json& v, const std::string& where, const char* what);

template <class E>
E getChoice(const JsonCtx& ctx, const nlohmann::json& v, const std::string& where, const ChoiceNames<E>& names) {
  const std::string list = choiceList(names, /*quoted=*/true);
  if (!v.is_string()) jsonFail(ctx, where, "expected one of " + list + ", got " + v.type_name());
  auto it = names.find(v.get<std::string>());
  if (it == names.end()) jsonFail(ctx, where, "expected one of " + list + ", got " + v.dump());
  return it->second;
}

}  // namespace montecl
