// scene_file.cpp: loadScene(): reads a scene file (JSON: camera, meshes, render settings) or a bare
// mesh (.obj, .ply, .gltf, .glb), validates every value, and reports bad input as one InputError
// line "<file>: <key>: <problem>". Unknown keys become warnings. Meshes are loaded by
// loadMeshFile() (mesh_loaders.h), per format by its extension.
#include <nlohmann/json.hpp>

#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <optional>

#include "scene/camera_basis.h"
#include "scene/json_fields.h"
#include "scene/load_util.h"
#include "scene/mesh_entry.h"
#include "scene/mesh_loaders.h"
#include "scene/environment_key.h"
#include "scene/lights_key.h"
#include "scene/mitsuba_scene.h"
#include "scene/pbrt_scene.h"
#include "scene/scene_readers.h"
#include "scene/scene.h"
#include "util/errors.h"

namespace montecl {
namespace {

using nlohmann::json;

using Ctx = JsonCtx;

[[noreturn]] void fail(const Ctx& ctx, const std::string& where, const std::string& problem) {
  jsonFail(ctx, where, problem);
}

std::string readSceneText(const Ctx& ctx) {
  std::string problem = fileProblem(ctx.file);
  if (!problem.empty()) fail(ctx, "", "cannot open: " + problem);
  std::ifstream in(ctx.file, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) fail(ctx, "", "read error");
  return text;
}

// Walks the JSON with nlohmann's SAX interface to find where parsing stops: the key path of the
// value being read ("camera.position[0]") and the byte position. Used after json::parse() threw an
// error that carries no position (out_of_range.406, a number overflowing a double).
class ErrorLocator : public nlohmann::json_sax<json> {
 public:
  std::string path() const {
    std::string out;
    for (const Frame& f : frames_)
      out += f.array ? "[" + std::to_string(f.index) + "]" : (out.empty() ? "" : ".") + f.key;
    return out;
  }
  std::size_t position = std::string::npos;
  std::string token;

  bool null() override { return value(); }
  bool boolean(bool) override { return value(); }
  bool number_integer(number_integer_t) override { return value(); }
  bool number_unsigned(number_unsigned_t) override { return value(); }
  bool number_float(number_float_t, const string_t&) override { return value(); }
  bool string(string_t&) override { return value(); }
  bool binary(binary_t&) override { return value(); }
  bool start_object(std::size_t) override { return open(false); }
  bool key(string_t& k) override {
    frames_.back().key = k;
    return true;
  }
  bool end_object() override { return close(); }
  bool start_array(std::size_t) override { return open(true); }
  bool end_array() override { return close(); }
  bool parse_error(std::size_t pos, const std::string& last, const nlohmann::detail::exception&) override {
    position = pos;
    token = last;
    return false;
  }

 private:
  struct Frame {
    bool array = false;
    std::string key;
    std::size_t index = 0;
  };
  bool value() {
    if (!frames_.empty() && frames_.back().array) ++frames_.back().index;
    return true;
  }
  bool open(bool array) {
    frames_.push_back({array, "", 0});
    return true;
  }
  bool close() {
    frames_.pop_back();
    return value();
  }
  std::vector<Frame> frames_;
};

// "line L, column C" of the byte at offset in text (1-based).
std::string lineColumn(const std::string& text, std::size_t offset) {
  offset = std::min(offset, text.size());
  std::size_t line = 1 + static_cast<std::size_t>(std::count(text.begin(), text.begin() + offset, '\n'));
  std::size_t lineStart = text.rfind('\n', offset == 0 ? 0 : offset - 1);
  std::size_t column = offset - (lineStart == std::string::npos || offset == 0 ? 0 : lineStart + 1) + 1;
  return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

// nlohmann's message "[json.exception.parse_error.101] parse error at line 3, column 5: syntax
// error ..." becomes where = "line 3, column 5", problem = "malformed JSON: syntax error ...".
json parseJson(const Ctx& ctx, const std::string& text) {
  checkJsonDepth(ctx.file, text.data(), text.size());
  try {
    return json::parse(text);
  } catch (const json::parse_error& e) {
    std::string what = e.what();
    std::size_t at = what.find(" at line ");
    std::size_t colon = at == std::string::npos ? at : what.find(": ", at);
    if (colon == std::string::npos) fail(ctx, "byte " + std::to_string(e.byte), "malformed JSON: " + what);
    fail(ctx, what.substr(at + 4, colon - at - 4), "malformed JSON: " + what.substr(colon + 2));
  } catch (const json::exception& e) {  // out_of_range.406: "number overflow parsing '1e400'"
    ErrorLocator where;
    json::sax_parse(text, &where);
    std::string problem = e.what();
    std::size_t close = problem.find("] ");
    if (close != std::string::npos) problem = problem.substr(close + 2);
    if (where.position == std::string::npos) fail(ctx, "(top level)", problem);
    const std::size_t start = where.position - std::min(where.position, where.token.size());
    const std::string key = where.path().empty() ? "(top level)" : where.path();
    fail(ctx, key, problem + " (" + lineColumn(text, start) + ")");
  }
}

// ---- camera ---------------------------------------------------------------------------------

// The scene file's camera: "auto", or an object whose missing position / target / up / fov_y come
// from the automatic framing (defaultCamera, the front view) once the meshes are loaded, and whose
// missing width / height are 512 (what a bare mesh gets).
struct CameraKeys {
  Camera cam;
  bool position = false, target = false, up = false, fovY = false;
  bool framed() const { return !(position && target && fovY); }  // needs the automatic framing
};

CameraKeys parseCamera(const Ctx& ctx, const json& root) {
  const json& v = requireKey(ctx, root, "", "camera");
  CameraKeys k;
  if (v.is_string() && v.get<std::string>() == "auto") return k;
  if (v.is_string()) fail(ctx, "camera", "expected an object or \"auto\", got '" + oneLine(v.get<std::string>(), 40) + "'");
  const json& j = requireObject(ctx, v, "camera");
  warnUnknownKeys(ctx, j, "camera",
                  {"position", "target", "up", "fov_y", "width", "height", "aperture_radius", "focus_distance"});
  Camera& cam = k.cam;
  if (const json* p = optionalKey(j, "position")) cam.position = getVec3(ctx, *p, "camera.position"), k.position = true;
  if (const json* t = optionalKey(j, "target")) cam.target = getVec3(ctx, *t, "camera.target"), k.target = true;
  if (const json* up = optionalKey(j, "up")) cam.up = getVec3(ctx, *up, "camera.up"), k.up = true;
  if (const json* f = optionalKey(j, "fov_y")) cam.fovY = getFloat(ctx, *f, "camera.fov_y"), k.fovY = true;
  const std::string sideRule = "a positive integer up to " + std::to_string(kMaxImageSide);
  const char* side = sideRule.c_str();
  if (const json* w = optionalKey(j, "width")) cam.width = getPositiveInt(ctx, *w, "camera.width", kMaxImageSide, side);
  if (const json* h = optionalKey(j, "height")) cam.height = getPositiveInt(ctx, *h, "camera.height", kMaxImageSide, side);
  if (!k.framed()) {
    const CameraProblem p = cameraBasisProblem(cam);  // the one camera rule (scene/camera_basis.h)
    if (!p.empty()) fail(ctx, p.key, p.problem);
  }
  if (const json* a = optionalKey(j, "aperture_radius")) {
    cam.apertureRadius = getFloat(ctx, *a, "camera.aperture_radius");
    if (!(cam.apertureRadius >= 0.0f)) fail(ctx, "camera.aperture_radius", "must be >= 0");
  }
  if (const json* f = optionalKey(j, "focus_distance")) {
    cam.focusDistance = getFloat(ctx, *f, "camera.focus_distance");
    if (!(cam.focusDistance > 0.0f)) fail(ctx, "camera.focus_distance", "must be > 0");
  }
  return k;
}

// The keys a scene file left out, from the automatic framing of the loaded scene's bounds.
Camera completeCamera(const Ctx& ctx, const Scene& scene, const CameraKeys& k) {
  if (!k.framed()) return k.cam;
  const Camera a = defaultCamera(scene.boundsMin, scene.boundsMax, k.cam.width, k.cam.height);
  Camera cam = k.cam;
  if (!k.position) cam.position = a.position;
  if (!k.target) cam.target = a.target;
  if (!k.up) cam.up = a.up;
  if (!k.fovY) cam.fovY = a.fovY;
  const CameraProblem p = cameraBasisProblem(cam);
  if (!p.empty()) fail(ctx, p.key, p.problem + " (with the automatic framing for the keys not given)");
  return cam;
}

// ---- render ---------------------------------------------------------------------------------

RenderSettings parseRender(const Ctx& ctx, const json& root) {
  const json* j = optionalKey(root, "render");
  return j ? parseRenderSettings(ctx, *j) : RenderSettings{};  // (scene/render_settings.h)
}

// ---- meshes ---------------------------------------------------------------------------------

std::vector<MeshEntry> parseMeshes(const Ctx& ctx, const json& root, Scene& scene) {
  const json& list = requireKey(ctx, root, "", "meshes");
  if (!list.is_array()) fail(ctx, "meshes", std::string("expected a list of meshes, got ") + list.type_name());
  if (list.empty()) fail(ctx, "meshes", "empty list (at least one mesh is needed)");
  std::vector<MeshEntry> meshes;
  for (std::size_t i = 0; i < list.size(); ++i)
    meshes.push_back(parseMeshEntry(ctx, list[i], "meshes[" + std::to_string(i) + "]",
                                    &scene.missingTextures));
  for (const MeshEntry& m : meshes) {  // report bad paths before spending time on loading
    std::string problem = fileProblem(m.path);
    if (!problem.empty()) fail(ctx, m.where, "cannot open '" + m.path + "': " + problem);
  }
  return meshes;
}

// Loads every mesh (any format, by extension) and applies its entry; returns whether a glTF
// mesh brought a camera (the first one, moved by its mesh's transform), stored in *camera.
bool loadMeshes(const Ctx& ctx, const std::vector<MeshEntry>& meshes, Scene& scene, Camera* camera) {
  bool hasCamera = false;
  std::string emptiedBy;  // the first entry whose transform dropped all of its mesh's triangles
  std::size_t emptiedCount = 0;
  for (const MeshEntry& m : meshes) {
    std::size_t firstTri = scene.triangles.size(), firstLight = scene.lights.size();
    Camera cam;
    if (loadMeshFile(m.path, scene, &ctx.warnings, &cam) && !hasCamera) {
      hasCamera = true;
      const glm::dmat4 t = m.placement(0);  // with instances: where the first copy is
      camera->position = glm::vec3(t * glm::dvec4(glm::dvec3(cam.position), 1.0));
      camera->target = glm::vec3(t * glm::dvec4(glm::dvec3(cam.target), 1.0));
      camera->up = glm::vec3(glm::dmat3(t) * glm::dvec3(cam.up));
      camera->fovY = cam.fovY;
      camera->width = cam.width;
      camera->height = cam.height;
    }
    const std::size_t loaded = scene.triangles.size() - firstTri;
    applyMeshEntry(ctx, scene, firstTri, firstLight, m);
    if (scene.triangles.size() == firstTri && emptiedBy.empty()) {
      emptiedBy = m.prefix + (m.instances.empty() ? ".transform" : ".instances");
      emptiedCount = loaded;
    }
  }
  // Every loader refuses a file without triangles, but a transform (scale 0, say) can make all of
  // them degenerate: the renderer cannot build a BVH over nothing, so say which entry did it.
  if (scene.triangles.empty())
    fail(ctx, emptiedBy.empty() ? "meshes" : emptiedBy,
         emptiedBy.empty() ? "the scene has no triangles"
                           : "leaves the scene with no triangles (all " + std::to_string(emptiedCount) +
                                 " of the mesh's triangles are degenerate after the transform)");
  recomputeBounds(scene);
  return hasCamera;
}

// Light selection weighs each emitting triangle by area * luminance(Le) in float, and the renderer
// sums those weights in float: an emission whose weight (or whose sum) overflows gives NaN and
// infinite pixels, so it is refused here, naming the material.
void checkEmissionPower(const Scene& scene) {
  float total = 0.0f;
  for (const SceneTriangle& t : scene.triangles) {
    const MaterialDesc& m = scene.materials[t.material];
    const glm::vec3& le = m.emission;
    if (le == glm::vec3(0.0f)) continue;
    const float lum = 0.2126f * le.x + 0.7152f * le.y + 0.0722f * le.z;
    const float area = 0.5f * glm::length(glm::cross(t.v[1] - t.v[0], t.v[2] - t.v[0]));
    const float power = lum * area;
    total += power;
    if (!std::isfinite(lum) || !std::isfinite(power) || !std::isfinite(total))
    {
      char value[96];
      std::snprintf(value, sizeof value, "%g, %g, %g", double(le.x), double(le.y), double(le.z));
      throwInputError(scene.path, "material '" + m.name + "'",
                      std::string("emission [") + value + "] too large: luminance x triangle area overflows a float");
    }
  }
}

// A bare mesh file: its own camera (glTF) when it has a usable one, else defaultCamera().
// Every texture the scene cannot open, in one line: the error (missing_textures error), or the
// warning (warn) for a scene that renders without them.
void reportMissingTextures(const Scene& scene, std::vector<std::string>& warnings) {
  if (scene.missingTextures.empty()) return;
  if (scene.render.missingTextures == MissingTextures::Error)
    throw InputError(missingTexturesError(scene, 0));
  warnings.push_back(missingTexturesText(scene, 0) +
                     "; rendered without them (each material's factor alone: missing_textures warn)");
}

Scene loadBareMesh(const std::string& path, std::vector<std::string>& warnings, std::optional<MissingTextures> missing,
                   std::optional<unsigned> gltfScene) {
  Scene scene;
  scene.path = path;
  if (missing) scene.render.missingTextures = *missing;
  scene.deferMissingTextures = true;
  Camera fileCamera;
  const bool hasCamera = loadMeshFile(path, scene, &warnings, &fileCamera, gltfScene);
  if (scene.fileScenes > 1 && !gltfScene)
    warnings.push_back(oneLine(path) + ": " + std::to_string(scene.fileScenes) + " scenes; scene " +
                       std::to_string(scene.fileScene) + " (the file's default) is used (--scene N picks scene N, from 0)");
  const CameraProblem fileProblem = hasCamera ? cameraBasisProblem(fileCamera) : CameraProblem{};
  if (hasCamera && fileProblem.empty()) {
    scene.camera = fileCamera;
  } else {
    if (hasCamera)
      warnings.push_back(oneLine(path) + ": camera: the file's camera cannot be used (" + fileProblem.key + " " +
                         fileProblem.problem + "), framing the model instead");
    scene.camera = defaultCamera(scene.boundsMin, scene.boundsMax, 512, 512);
  }
  const CameraProblem p = cameraBasisProblem(scene.camera);
  if (!p.empty())
    throwInputError(oneLine(path), "automatic camera",
                    "cannot frame the model: " + p.key + " " + p.problem +
                        "; write a scene file with a camera for it");
  checkEmissionPower(scene);
  applyBareModelDefaults(scene);
  reportMissingTextures(scene, warnings);
  return scene;
}

}  // namespace

void applyBareModelDefaults(Scene& scene) {
  scene.render.integrator = Integrator::Path;
  bool lit = !scene.lights.empty();
  for (const SceneTriangle& t : scene.triangles) {
    const MaterialDesc& m = scene.materials[t.material];
    lit = lit || (m.emission != glm::vec3(0.0f) && m.emissionTexture.empty());
  }
  scene.environment = EnvironmentDesc{};
  scene.environment.enabled = true;
  scene.environment.radiance = glm::vec3(lit ? kLitModelSkyRadiance : kDefaultSkyRadiance);
  scene.defaultsNote = lit ? "a white sky of radiance 0.25 (the model brings its own lights; --env none for those "
                             "alone, --env R,G,B or a map file for another)"
                           : "a white sky of radiance 1 (--env none, R,G,B or a map file for another)";
}

Scene loadScene(const std::string& path, std::vector<std::string>& warnings, std::optional<MissingTextures> missing,
                std::optional<unsigned> gltfScene) {
  const SceneReader reader = sceneReaderOf(path);  // the table of formats (scene/scene_readers.h)
  if (reader == SceneReader::Mesh) return loadBareMesh(path, warnings, missing, gltfScene);
  if (gltfScene) throwSceneOptionError(path);  // a scene file: its glTF meshes load their default scene
  if (reader == SceneReader::Pbrt || reader == SceneReader::Mitsuba) {
    Scene scene = reader == SceneReader::Pbrt ? loadPbrtScene(path, warnings, missing)     // scene/pbrt_scene.h
                                              : loadMitsubaScene(path, warnings, missing);  // scene/mitsuba_scene.h
    checkEmissionPower(scene);
    return scene;
  }
  Ctx ctx{path, warnings};
  const std::string text = readSceneText(ctx);
  // A file of another kind (x.stl, a pbrt-v3 .lxs) is not reported as malformed JSON: JSON is
  // tried under another extension only when the text starts like a scene file, with '{'.
  const std::size_t first = text.find_first_not_of(" \t\r\n");
  if (reader == SceneReader::None && !lowerExtension(path).empty() && (first == std::string::npos || text[first] != '{'))
    throwInputError(oneLine(path), "", "montecl reads " + readableExtensions());
  json root = parseJson(ctx, text);
  requireObject(ctx, root, "(top level)");
  warnUnknownKeys(ctx, root, "", {"camera", "meshes", "render", "environment", "lights"});
  Scene scene;
  scene.path = path;
  scene.inputFiles.push_back(path);
  // The camera is required unless a glTF mesh brings one (the scene file's wins when both are given).
  const bool hasCamera = optionalKey(root, "camera") != nullptr;
  CameraKeys cameraKeys;
  if (hasCamera) cameraKeys = parseCamera(ctx, root);
  scene.render = parseRender(ctx, root);
  if (missing) scene.render.missingTextures = *missing;
  scene.deferMissingTextures = true;
  if (const json* env = optionalKey(root, "environment")) {
    scene.environment = parseEnvironmentKey(path, *env, warnings);
    if (!scene.environment.file.empty()) scene.inputFiles.push_back(scene.environment.file);
  }
  if (const json* lights = optionalKey(root, "lights")) scene.lights = parseLightsKey(ctx, *lights);
  Camera meshCamera;
  const bool hasMeshCamera = loadMeshes(ctx, parseMeshes(ctx, root, scene), scene, &meshCamera);
  if (hasCamera) scene.camera = completeCamera(ctx, scene, cameraKeys);
  if (!hasCamera) {
    if (!hasMeshCamera)
      fail(ctx, "camera", "missing required key (and no glTF mesh has a camera); \"camera\": \"auto\" frames the scene");
    const CameraProblem p = cameraBasisProblem(meshCamera);
    if (!p.empty())
      fail(ctx, "camera", "missing, and the glTF mesh's camera cannot be used (" + p.key + " " + p.problem + ")");
    scene.camera = meshCamera;
  }
  checkEmissionPower(scene);
  reportMissingTextures(scene, warnings);
  return scene;
}

}  // namespace montecl
