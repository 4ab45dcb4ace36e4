// mesh_entry.cpp: parsing and applying a scene file's mesh entry (see mesh_entry.h).
#include "scene/mesh_entry.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <utility>

#include "scene/load_util.h"
#include "scene/material_params.h"
#include "scene/scene_instances.h"
#include "scene/value_limits.h"
#include "util/host_memory.h"

namespace montecl {
namespace {

using nlohmann::json;

std::string resolvePath(const std::string& sceneFile, const std::string& file) {
  std::filesystem::path folder = std::filesystem::path(sceneFile).parent_path();
  return (folder / file).lexically_normal().string();
}

// A texture named in the scene file: resolved against its folder, and it must exist, unless
// missing records it ("" returned: the override is then not given).
std::string texturePath(const JsonCtx& ctx, const json& v, const std::string& where, std::vector<MissingTexture>* missing) {
  const std::string path = resolvePath(ctx.file, getString(ctx, v, where, "a file name"));
  const std::string problem = fileProblem(path);
  if (!problem.empty() && !missing) jsonFail(ctx, where, "cannot open '" + path + "': " + problem);
  if (!problem.empty()) {
    noteMissingTexture(*missing, {ctx.file, where, "cannot open '" + path + "': " + problem, where + " '" + path + "'"});
    return "";
  }
  return path;
}

float getUnit(const JsonCtx& ctx, const json& v, const std::string& where) {
  const float f = getFloat(ctx, v, where);
  if (f < 0.0f || f > 1.0f) jsonFail(ctx, where, "must be in [0, 1]");
  return f;
}

void parseMaterial(const JsonCtx& ctx, const json& j, const std::string& prefix, MaterialOverride& o,
                   std::vector<MissingTexture>* missing) {
  const auto texture = [&](const json& v, const std::string& where, bool& given, std::string& path) {
    path = texturePath(ctx, v, where, missing);
    given = !path.empty();
  };
  requireObject(ctx, j, prefix);
  warnUnknownKeys(ctx, j, prefix,
                  {"type", "albedo", "albedo_texture", "alpha_texture", "alpha_cutoff", "emission",
                   "two_sided_emission", "specular", "specular_exponent", "eta", "k", "metal", "alpha",
                   "roughness", "ior", "metallic", "emission_texture", "normal_texture", "normal_scale",
                   "metallic_roughness_texture", "thickness", "max_depth", "samples", "base_alpha",
                   "distribution", "specular_reflectance", "clearcoat", "clearcoat_roughness", "sheen_color",
                   "sheen_roughness"});
  MaterialDesc& d = o.value;
  if (const json* v = optionalKey(j, "type")) {  // the material kind (kernels/shared/material_kinds.h)
    const std::string name = getString(ctx, *v, prefix + ".type", "a material type");
    if (!materialKindFromName(name.c_str(), d.kind))
      jsonFail(ctx, prefix + ".type", "unknown material type '" + oneLine(name, 60) + "' (known: " + materialKindNames() + ")");
    o.kind = true;
  }
  o.kindParams = parseKindParams(ctx, j, prefix, d);
  if (const json* v = optionalKey(j, "albedo")) o.albedo = true, d.albedo = getColor(ctx, *v, prefix + ".albedo");
  if (const json* v = optionalKey(j, "albedo_texture"))
    texture(*v, prefix + ".albedo_texture", o.albedoTexture, d.albedoTexture);
  if (const json* v = optionalKey(j, "alpha_texture"))
    texture(*v, prefix + ".alpha_texture", o.alphaTexture, d.alphaTexture);
  if (const json* v = optionalKey(j, "alpha_cutoff"))
    o.alphaCutoff = true, d.alphaCutoff = getUnit(ctx, *v, prefix + ".alpha_cutoff");
  if (const json* v = optionalKey(j, "emission")) o.emission = true, d.emission = getColor(ctx, *v, prefix + ".emission");
  if (const json* v = optionalKey(j, "two_sided_emission"))
    o.twoSided = true, d.twoSidedEmission = getBool(ctx, *v, prefix + ".two_sided_emission");
  if (const json* v = optionalKey(j, "emission_texture"))
    texture(*v, prefix + ".emission_texture", o.emissionTexture, d.emissionTexture);
  if (const json* v = optionalKey(j, "normal_texture"))
    texture(*v, prefix + ".normal_texture", o.normalTexture, d.normalTexture);
  if (const json* v = optionalKey(j, "metallic_roughness_texture"))  // glTF's: B metallic, G roughness, linear
    texture(*v, prefix + ".metallic_roughness_texture", o.metallicRoughnessTexture, d.metallicRoughnessTexture);
  if (const json* v = optionalKey(j, "normal_scale")) {
    o.normalScale = true;
    d.normalScale = getFloat(ctx, *v, prefix + ".normal_scale");
    if (!std::isfinite(d.normalScale)) jsonFail(ctx, prefix + ".normal_scale", "must be finite");
  }
  if (const json* v = optionalKey(j, "specular")) {
    o.specular = true;
    d.specular = getColor(ctx, *v, prefix + ".specular");
    if (d.specular.x > 1 || d.specular.y > 1 || d.specular.z > 1) jsonFail(ctx, prefix + ".specular", "components must be in [0, 1]");
  }
  if (const json* v = optionalKey(j, "specular_exponent")) {
    o.specularExponent = true;
    d.specularExponent = getFloat(ctx, *v, prefix + ".specular_exponent");
    if (d.specularExponent < 0.0f) jsonFail(ctx, prefix + ".specular_exponent", "must be >= 0");
  }
}

glm::dvec3 nonZeroScale(const JsonCtx& ctx, const json& v, const std::string& where) {
  glm::dvec3 s = v.is_number() ? glm::dvec3(getFloat(ctx, v, where)) : glm::dvec3(getVec3(ctx, v, where));
  if (s.x == 0.0 || s.y == 0.0 || s.z == 0.0) jsonFail(ctx, where, "must not be 0 (it would flatten the mesh)");
  return s;
}

glm::dmat4 parseTransform(const JsonCtx& ctx, const json& j, const std::string& prefix) {
  requireObject(ctx, j, prefix);
  warnUnknownKeys(ctx, j, prefix, {"scale", "rotate", "translate", "matrix"});
  if (const json* m = optionalKey(j, "matrix")) {
    const std::string where = prefix + ".matrix";
    for (const char* k : {"scale", "rotate", "translate"})
      if (optionalKey(j, k)) jsonFail(ctx, childKey(prefix, k), "give either \"matrix\" or scale/rotate/translate, not both");
    if (!m->is_array() || m->size() != 16)
      jsonFail(ctx, where, std::string("expected 16 numbers (a row-major 4x4 matrix), got ") +
                               (m->is_array() ? "an array of " + std::to_string(m->size()) : std::string(m->type_name())));
    glm::dmat4 t(0.0);
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) t[c][r] = getFloat(ctx, (*m)[std::size_t(4 * r + c)], where + "[" + std::to_string(4 * r + c) + "]");
    if (t[0][3] != 0.0 || t[1][3] != 0.0 || t[2][3] != 0.0 || t[3][3] != 1.0)
      jsonFail(ctx, where, "the last row must be 0 0 0 1 (no projective transforms)");
    if (glm::determinant(glm::dmat3(t)) == 0.0) jsonFail(ctx, where, "singular (it would flatten the mesh)");
    return t;
  }
  glm::dmat4 t(1.0);
  if (const json* v = optionalKey(j, "translate")) t = glm::translate(t, glm::dvec3(getVec3(ctx, *v, prefix + ".translate")));
  if (const json* v = optionalKey(j, "rotate")) {
    const std::string where = prefix + ".rotate";
    if (!v->is_array() || v->size() != 4) jsonFail(ctx, where, "expected [axis x, axis y, axis z, degrees]");
    glm::dvec3 axis(getFloat(ctx, (*v)[0], where + "[0]"), getFloat(ctx, (*v)[1], where + "[1]"),
                    getFloat(ctx, (*v)[2], where + "[2]"));
    const double degrees = getFloat(ctx, (*v)[3], where + "[3]");
    if (axis == glm::dvec3(0.0)) jsonFail(ctx, where, "the axis must not be the zero vector");
    t = glm::rotate(t, glm::radians(degrees), glm::normalize(axis));
  }
  if (const json* v = optionalKey(j, "scale")) t = glm::scale(t, nonZeroScale(ctx, *v, prefix + ".scale"));
  return t;  // translate * rotate * scale: scale first, then rotate, then translate
}

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

void transformTriangles(const JsonCtx& ctx, Scene& scene, std::size_t firstTri, const glm::dmat4& m, const std::string& key) {
  const Placement placement(m);
  std::size_t out = firstTri;
  for (std::size_t i = firstTri; i < scene.triangles.size(); ++i) {
    SceneTriangle t = scene.triangles[i];
    TriangleCorners c = cornersOf(scene, i);  // colours and tangents follow their triangle
    const Placed placed = placeTriangle(t, c, placement);
    if (placed == Placed::OutOfRange) jsonFail(ctx, key, "moves vertices out of float range");
    if (placed == Placed::Degenerate) {
      ++scene.degenerateDropped;
      continue;
    }
    putCorners(scene, out, c);
    scene.triangles[out++] = t;
  }
  scene.triangles.resize(out);
  truncateCorners(scene, out);
}

void overrideMaterials(const JsonCtx& ctx, Scene& scene, std::size_t firstTri, const MeshEntry& mesh) {
  const MaterialOverride& o = mesh.material;
  std::vector<std::int64_t> copyOf(scene.materials.size(), -1);
  for (std::size_t t = firstTri; t < scene.triangles.size(); ++t) {
    std::uint32_t& m = scene.triangles[t].material;
    if (copyOf[m] < 0) {
      MaterialDesc d = scene.materials[m];
      d.name += " (" + mesh.prefix + " override)";
      if (o.kind) {
        // The file's metallic-roughness texture and transmission (and its tint) belong to its kind.
        if (d.kind != o.value.kind)
          d.metallicRoughnessTexture.clear(), d.transmission = 0.0f, d.transmissionTinted = false,
          d.transmissionTexture.clear();
        d.kind = o.value.kind;
      }
      if (o.metallicRoughnessTexture) {
        if (d.kind != MCL_MATERIAL_metal_rough)
          jsonFail(ctx, mesh.prefix + ".material.metallic_roughness_texture",
                   "is read by the material type metal_rough only (this mesh's material is " +
                       std::string(materialKindName(d.kind)) + ")");
        d.metallicRoughnessTexture = o.value.metallicRoughnessTexture;
      }
      if (o.albedo) d.albedo = o.value.albedo;
      if (o.albedoTexture) {
        d.albedoTexture = o.value.albedoTexture;
        d.albedoSampling = TextureSampling{};  // a texture of the scene file's is read as it is
        if (!o.albedo) d.albedo = glm::vec3(1.0f);  // the texture as it is
      }
      if (o.alphaTexture || o.albedoTexture) d.cutoutHint.clear();  // the MTL's map_Kd is no longer alone
      if (o.alphaTexture) d.alphaTexture = o.value.alphaTexture, d.alphaSampling = TextureSampling{};
      if (o.alphaCutoff) d.alphaCutoff = o.value.alphaCutoff, d.alphaBlend = false;  // a cut-out, even of a BLEND material
      if (o.emission) d.emission = o.value.emission;
      if (o.emissionTexture) {
        d.emissionTexture = o.value.emissionTexture;
        d.emissionSampling = TextureSampling{};
        if (!o.emission) d.emission = glm::vec3(1.0f);  // the texture as it is
      }
      if (o.normalTexture) d.normalTexture = o.value.normalTexture, d.normalSampling = TextureSampling{};
      if (o.normalScale) d.normalScale = o.value.normalScale;
      if (o.twoSided) d.twoSidedEmission = o.value.twoSidedEmission;
      if (o.specular) d.specular = o.value.specular;
      if (o.specularExponent) d.specularExponent = o.value.specularExponent;
      if (o.kindParams) {
        d.eta = o.value.eta, d.k = o.value.k, d.ior = o.value.ior, d.kindAlpha = o.value.kindAlpha;
        d.metallic = o.value.metallic, d.roughness = o.value.roughness;
        d.thickness = o.value.thickness, d.layerMaxDepth = o.value.layerMaxDepth;
        d.layerSamples = o.value.layerSamples, d.baseAlpha = o.value.baseAlpha;
        d.beckmann = o.value.beckmann, d.conductorFactor = o.value.conductorFactor;
        d.clearcoat = o.value.clearcoat, d.clearcoatRoughness = o.value.clearcoatRoughness;
        d.sheenColor = o.value.sheenColor, d.sheenRoughness = o.value.sheenRoughness;
      }
      copyOf[m] = static_cast<std::int64_t>(scene.materials.size());
      scene.materials.push_back(d);
    }
    m = static_cast<std::uint32_t>(copyOf[m]);
  }
}

}  // namespace

MeshEntry parseMeshEntry(const JsonCtx& ctx, const json& j, const std::string& prefix, std::vector<MissingTexture>* missing) {
  requireObject(ctx, j, prefix);
  warnUnknownKeys(ctx, j, prefix, {"file", "emission", "two_sided_emission", "transform", "instances", "material"});
  MeshEntry m;
  m.prefix = prefix;
  m.where = prefix + ".file";
  m.path = resolvePath(ctx.file, getString(ctx, requireKey(ctx, j, prefix, "file"), m.where, "a file name"));
  if (const json* v = optionalKey(j, "material")) parseMaterial(ctx, *v, prefix + ".material", m.material, missing);
  if (const json* e = optionalKey(j, "emission")) {
    if (m.material.emission) jsonFail(ctx, prefix + ".emission", "also given as " + prefix + ".material.emission: give one");
    m.material.emission = true;
    m.material.value.emission = getColor(ctx, *e, prefix + ".emission");
  }
  if (const json* t = optionalKey(j, "two_sided_emission")) {
    if (m.material.twoSided)
      jsonFail(ctx, prefix + ".two_sided_emission", "also given as " + prefix + ".material.two_sided_emission: give one");
    m.material.twoSided = true;
    m.material.value.twoSidedEmission = getBool(ctx, *t, prefix + ".two_sided_emission");
  }
  if (const json* t = optionalKey(j, "transform")) {
    m.hasTransform = true;
    m.transform = parseTransform(ctx, *t, prefix + ".transform");
  }
  if (const json* list = optionalKey(j, "instances")) {
    const std::string where = prefix + ".instances";
    if (!list->is_array() || list->empty())
      jsonFail(ctx, where, std::string("expected a non-empty list of transforms, got ") +
                               (list->is_array() ? "an empty list" : std::string(list->type_name())));
    m.instances.reserve(list->size());
    for (std::size_t k = 0; k < list->size(); ++k)
      m.instances.push_back(parseTransform(ctx, (*list)[k], where + "[" + std::to_string(k) + "]"));
  }
  return m;
}

namespace {

// The lights a glTF mesh brought, placed by the entry's transform as its triangles are (a spot's
// axis and a directional light's direction turned by it).
void transformLights(const JsonCtx& ctx, Scene& scene, std::size_t firstLight, const glm::dmat4& m, const std::string& key) {
  for (std::size_t i = firstLight; i < scene.lights.size(); ++i) {
    LightDesc& l = scene.lights[i];
    l.position = glm::vec3(m * glm::dvec4(glm::dvec3(l.position), 1.0));
    const glm::dvec3 d = glm::dmat3(m) * glm::dvec3(l.direction);
    if (!finite(l.position) || !(glm::length(d) > 0.0))
      jsonFail(ctx, key, "moves a light of the mesh out of float range");
    l.direction = glm::vec3(glm::normalize(d));
  }
}

// The entry's instances: the loaded triangles and lights (materials overridden once, so the
// copies share them) copied once per instance and placed; the memory check counts every copy
// before one is made.
void applyInstances(const JsonCtx& ctx, Scene& scene, std::size_t firstTri, std::size_t firstLight,
                    const MeshEntry& mesh) {
  const std::uint64_t copies = mesh.instances.size(), tris = scene.triangles.size() - firstTri;
  const std::string tooMany = sceneMemoryRefusal(std::uint64_t(firstTri) + copies * tris, sizeof(SceneTriangle));
  if (!tooMany.empty()) jsonFail(ctx, mesh.prefix + ".instances", std::to_string(copies) + " copies of the mesh " + tooMany);
  const std::vector<SceneTriangle> triangles(scene.triangles.begin() + std::ptrdiff_t(firstTri), scene.triangles.end());
  const std::vector<LightDesc> lights(scene.lights.begin() + std::ptrdiff_t(firstLight), scene.lights.end());
  scene.triangles.resize(firstTri);
  scene.lights.resize(firstLight);
  for (std::size_t k = 0; k < mesh.instances.size(); ++k) {
    const std::size_t t0 = scene.triangles.size(), l0 = scene.lights.size();
    scene.triangles.insert(scene.triangles.end(), triangles.begin(), triangles.end());
    scene.lights.insert(scene.lights.end(), lights.begin(), lights.end());
    const std::string key = mesh.prefix + ".instances[" + std::to_string(k) + "]";
    transformTriangles(ctx, scene, t0, mesh.placement(k), key);
    transformLights(ctx, scene, l0, mesh.placement(k), key);
  }
}

// Whether the entry's instances can stay one mesh placed several times: it brought no lights and
// no emitting material (the emitter table and the lights are world space, so those stay copies).
bool keepsInstances(const Scene& scene, std::size_t firstTri, std::size_t firstLight) {
  return scene.lights.size() == firstLight && scene.triangles.size() > firstTri && !trianglesEmit(scene, firstTri);
}

// The entry's triangles stay as loaded (object space) as one mesh range, placed once per instance.
void recordInstances(const JsonCtx& ctx, Scene& scene, std::size_t firstTri, const MeshEntry& mesh) {
  const std::string tooMany = instanceMemoryRefusal(std::uint64_t(scene.instances.size()) + mesh.instances.size());
  if (!tooMany.empty()) jsonFail(ctx, mesh.prefix + ".instances", "placing the mesh " + tooMany);
  const std::uint32_t range = static_cast<std::uint32_t>(scene.meshRanges.size());
  scene.meshRanges.push_back({static_cast<std::uint32_t>(firstTri), static_cast<std::uint32_t>(scene.triangles.size() - firstTri)});
  const std::vector<glm::vec3> corners = rangeBoxCorners(scene, scene.meshRanges[range]);
  for (std::size_t k = 0; k < mesh.instances.size(); ++k) {
    const glm::dmat4 m = mesh.placement(k);
    if (const std::string bad = placementProblem(m, corners); !bad.empty())
      jsonFail(ctx, mesh.prefix + ".instances[" + std::to_string(k) + "]", bad);
    scene.instances.push_back({range, m});
  }
}

}  // namespace

// The entry's override textures, as inputs of the render (the output must not replace them).
void addInputFiles(Scene& scene, const MeshEntry& mesh);

void applyMeshEntry(const JsonCtx& ctx, Scene& scene, std::size_t firstTri, std::size_t firstLight,
                    const MeshEntry& mesh) {
  // Meshes the file itself instanced (a glTF's shared meshes): under the entry's own instances they
  // become placed copies (as before instancing); under a transform or material override they stay
  // instances, the transform composed after their placements, unless the override makes them emit.
  std::size_t firstRange = scene.meshRanges.size();
  while (firstRange > 0 && scene.meshRanges[firstRange - 1].firstTri >= firstTri) --firstRange;
  if (firstRange < scene.meshRanges.size() && !mesh.instances.empty())
    if (const std::string tooMany = flattenInstances(scene, firstRange); !tooMany.empty())
      jsonFail(ctx, mesh.prefix + ".instances", tooMany);
  if (firstRange < scene.meshRanges.size()) {
    DetachedRanges ranges = detachRanges(scene, firstRange);
    if (mesh.hasTransform) transformTriangles(ctx, scene, firstTri, mesh.transform, mesh.prefix + ".transform");
    if (mesh.hasTransform) transformLights(ctx, scene, firstLight, mesh.transform, mesh.prefix + ".transform");
    if (mesh.material.any()) overrideMaterials(ctx, scene, firstTri, mesh);
    const std::size_t rangeTri = scene.triangles.size();
    attachRanges(scene, firstRange, std::move(ranges));
    if (mesh.material.any()) overrideMaterials(ctx, scene, rangeTri, mesh);
    if (mesh.hasTransform) {
      std::vector<SceneInstance> placed;
      for (const SceneInstance& in : scene.instances)
        if (in.range >= firstRange) placed.push_back(in);
      scene.instances.erase(std::remove_if(scene.instances.begin(), scene.instances.end(),
                                           [&](const SceneInstance& in) { return in.range >= firstRange; }),
                            scene.instances.end());
      for (const SceneInstance& in : placed)
        if (const std::string bad = addPlacements(scene, in.range, {mesh.transform * in.objectToWorld}); !bad.empty())
          jsonFail(ctx, mesh.prefix + ".transform", bad);
    }
    if (trianglesEmit(scene, rangeTri))  // emitters are world space: copies
      if (const std::string tooMany = flattenInstances(scene, firstRange); !tooMany.empty())
        jsonFail(ctx, mesh.prefix, "emitting, " + tooMany);
    addInputFiles(scene, mesh);
    return;
  }
  if (!mesh.instances.empty()) {
    if (mesh.material.any()) overrideMaterials(ctx, scene, firstTri, mesh);
    if (keepsInstances(scene, firstTri, firstLight))
      recordInstances(ctx, scene, firstTri, mesh);
    else
      applyInstances(ctx, scene, firstTri, firstLight, mesh);
  } else {
    if (mesh.hasTransform) transformTriangles(ctx, scene, firstTri, mesh.transform, mesh.prefix + ".transform");
    if (mesh.hasTransform) transformLights(ctx, scene, firstLight, mesh.transform, mesh.prefix + ".transform");
    if (mesh.material.any()) overrideMaterials(ctx, scene, firstTri, mesh);
  }
  addInputFiles(scene, mesh);
}

void addInputFiles(Scene& scene, const MeshEntry& mesh) {
  if (mesh.material.albedoTexture) scene.inputFiles.push_back(mesh.material.value.albedoTexture);
  if (mesh.material.alphaTexture) scene.inputFiles.push_back(mesh.material.value.alphaTexture);
  if (mesh.material.emissionTexture) scene.inputFiles.push_back(mesh.material.value.emissionTexture);
  if (mesh.material.normalTexture) scene.inputFiles.push_back(mesh.material.value.normalTexture);
  if (mesh.material.metallicRoughnessTexture) scene.inputFiles.push_back(mesh.material.value.metallicRoughnessTexture);
}

void recomputeBounds(Scene& scene) {
  scene.boundsMin = scene.boundsMax = glm::vec3(0.0f);
  if (scene.triangles.empty()) return;
  if (!scene.instances.empty() || !scene.meshRanges.empty()) {  // world triangles and placed boxes
    const std::vector<std::uint8_t> instanced = instancedTriangles(scene);
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (std::size_t i = 0; i < scene.triangles.size(); ++i)
      if (!instanced[i])
        for (const glm::vec3& v : scene.triangles[i].v) lo = glm::min(lo, v), hi = glm::max(hi, v);
    for (const glm::vec3& c : instanceBoxCorners(scene)) lo = glm::min(lo, c), hi = glm::max(hi, c);
    if (lo.x <= hi.x) scene.boundsMin = lo, scene.boundsMax = hi;
    return;
  }
  scene.boundsMin = scene.boundsMax = scene.triangles[0].v[0];
  for (const SceneTriangle& t : scene.triangles)
    for (const glm::vec3& v : t.v) {
      scene.boundsMin = glm::min(scene.boundsMin, v);
      scene.boundsMax = glm::max(scene.boundsMax, v);
    }
}

}  // namespace montecl
