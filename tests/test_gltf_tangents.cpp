// test_gltf_tangents.cpp: glTF TANGENT (kernels/shared/normal_map.h file_tangent_to_world; read by
// host/scene/gltf_mesh.cpp, placed by scene_instances.cpp Placement::tangent): a normal-mapped
// plane written here renders like the UV-made frame when its TANGENT is that frame; a TANGENT
// turned 90 degrees about the normal, one with w = -1, a mirroring node (placed once, and twice
// through a two-level BVH) or mesh transform and a stretching node each put the N AOV on the
// analytic mapped normal of their frame; quantized (normalized SHORT) tangents load; a
// TANGENT of the wrong type, component type or count is one line naming the file and the
// attribute, exit 2, nothing written; the conformance set's tangent case shades by its tangents.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "bvh/bvh_instances.h"
#include "cl/devices.h"
#include "cli_runner.h"
#include "conformance/scenes.h"
#include "mesh_files.h"
#include "render/wavefront.h"
#include "test_images.h"

namespace test_file_gltf_tangents {  // keeps this file's helpers apart in a unity batch

using namespace montecl;
using namespace montecl_test;

namespace {

constexpr double kPi = 3.14159265358979323846;
// The texel: the unit normal tilted 30 degrees from N toward (cos 60, sin 60) of the tangent plane.
const int kTexel[3] = {159, 183, 238};
double decode(int c8) { return 2.0 * c8 / 255.0 - 1.0; }
// n.png in dir: every texel kTexel.
void writeNormalMap(TempDir& dir) {
  writeImage8(dir.file("n.png"), 4, 4, 3, [](int, int, int c) { return kTexel[c]; });
}

// The plane y = 0 over [-2, 2]^2 (normal +y) with montecl UVs u = du.(x, z) + 0.5, v = dv.(x, z) +
// 0.5 (the file holds glTF's 1 - v), and dP/du, dP/dv of that map in world space.
struct UvMap {
  glm::dvec2 du, dv;
  glm::dvec3 dPdu() const { return glm::dvec3(dv.y, 0, -dv.x) / (du.x * dv.y - du.y * dv.x); }
  glm::dvec3 dPdv() const { return glm::dvec3(-du.y, 0, du.x) / (du.x * dv.y - du.y * dv.x); }
};
const glm::dvec3 kN(0, 1, 0);
const glm::vec3 kCorners[4] = {{-2, 0, 2}, {2, 0, 2}, {2, 0, -2}, {-2, 0, -2}};

// The tangent the per-triangle rule makes: xyz along dP/du, w the UV map's handedness (the sign of
// (N x dP/du) . dP/dv).
glm::dvec4 uvTangent(const UvMap& mp) {
  const double hand = glm::dot(glm::cross(kN, mp.dPdu()), mp.dPdv()) < 0.0 ? -1.0 : 1.0;
  return glm::dvec4(glm::normalize(mp.dPdu()), hand);
}

// The analytic mapped normal of the texel in the frame of tangent t (B = w N x T).
glm::dvec3 mappedNormal(const glm::dvec4& t) {
  const glm::dvec3 T = glm::dvec3(t), B = t.w * glm::cross(kN, T);
  return glm::normalize(T * decode(kTexel[0]) + B * decode(kTexel[1]) + kN * decode(kTexel[2]));
}

void putFloats(std::string& bytes, std::initializer_list<float> v) {
  for (float f : v) bytes.append(reinterpret_cast<const char*>(&f), sizeof f);
}

// The plane as a glTF: POSITION, TEXCOORD_0, TANGENT (every corner `tangent` when given), indices;
// a Lambert material whose normalTexture is n.png; one node (scaled by `scale`), and with
// `instanced` a second one far to the side, so the mesh is placed twice through a two-level BVH.
nlohmann::json planeGltf(const UvMap& mp, const glm::vec4* tangent, glm::dvec3 scale = glm::dvec3(1.0),
                         bool instanced = false) {
  std::string bytes;
  for (const glm::vec3& p : kCorners) putFloats(bytes, {p.x, p.y, p.z});
  for (const glm::vec3& p : kCorners) {
    const double u = mp.du.x * p.x + mp.du.y * p.z + 0.5, v = mp.dv.x * p.x + mp.dv.y * p.z + 0.5;
    putFloats(bytes, {float(u), float(1.0 - v)});
  }
  if (tangent)
    for (int k = 0; k < 4; ++k) putFloats(bytes, {tangent->x, tangent->y, tangent->z, tangent->w});
  const std::uint32_t idx[6] = {0, 1, 2, 0, 2, 3};
  const std::size_t indexOffset = bytes.size();
  bytes.append(reinterpret_cast<const char*>(idx), sizeof idx);
  using J = nlohmann::json;
  J g = {{"asset", {{"version", "2.0"}}}, {"scene", 0}, {"scenes", {{{"nodes", {0}}}}}};
  g["nodes"] = {{{"mesh", 0}}};
  g["nodes"][0]["scale"] = {scale.x, scale.y, scale.z};
  if (instanced) g["nodes"].push_back({{"mesh", 0}, {"translation", {100, 0, 0}}}), g["scenes"][0]["nodes"] = {0, 1};
  g["buffers"] = {{{"uri", "data:application/octet-stream;base64," + base64(bytes)}, {"byteLength", bytes.size()}}};
  g["bufferViews"] = {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 48}},
                      {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 32}},
                      {{"buffer", 0}, {"byteOffset", indexOffset}, {"byteLength", 24}}};
  g["accessors"] = {{{"bufferView", 0}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"},
                     {"min", {-2, 0, -2}}, {"max", {2, 0, 2}}},
                    {{"bufferView", 1}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}},
                    {{"bufferView", 2}, {"componentType", 5125}, {"count", 6}, {"type", "SCALAR"}}};
  J attributes = {{"POSITION", 0}, {"TEXCOORD_0", 1}};
  if (tangent) {
    g["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", 80}, {"byteLength", 64}});
    g["accessors"].push_back({{"bufferView", 3}, {"componentType", 5126}, {"count", 4}, {"type", "VEC4"}});
    attributes["TANGENT"] = 3;
  }
  g["meshes"] = {{{"primitives", {{{"attributes", attributes}, {"indices", 2}, {"material", 0}}}}}};
  g["materials"] = {{{"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.6, 0.7, 1}}, {"metallicFactor", 0},
                                               {"roughnessFactor", 1}}},
                     {"normalTexture", {{"index", 0}}}}};
  g["textures"] = {{{"source", 0}}};
  g["images"] = {{{"uri", "n.png"}}};
  return g;
}

// The scene or glTF file `name` in dir seen straight down from 1 above the origin (8 x 8, every
// pixel on the plane), lit by a directional light, direct light sampling, with AOVs.
Film renderFile(TempDir& dir, const std::string& name, bool instanced = false) {
  std::vector<std::string> warnings;
  Scene s = loadScene(dir.file(name), warnings);
  REQUIRE(s.instances.empty() == !instanced);
  for (const std::string& w : warnings) CHECK_MESSAGE(w.find("TANGENT") == std::string::npos, w);
  s.camera.position = {0.1f, 1.0f, -0.05f};
  s.camera.target = {0.1f, 0.0f, -0.05f};
  s.camera.up = {0, 0, -1};
  s.camera.fovY = 60.0f;
  s.camera.width = s.camera.height = 8;
  s.render.spp = 2;
  s.render.integrator = Integrator::Direct;
  s.render.directSampling = DirectSampling::Light;
  s.environment.enabled = false;
  LightDesc l;
  l.kind = PunctualKind::Directional;
  l.direction = glm::normalize(glm::vec3(-0.6f, -1.0f, 0.3f));
  l.color = glm::vec3(0.7f, 0.4f, 0.2f);
  s.lights = {l};
  static const DeviceInfo device = selectDevice("");
  RenderOptions o;
  o.aovs = true;
  Bvh bvh = buildSceneBvh(s);
  WavefrontRenderer renderer(device, o);
  RenderStats stats;
  return renderer.render(s, bvh, stats);
}

// renderFile of the glTF g, written as `name` beside n.png in dir.
Film renderPlane(TempDir& dir, const nlohmann::json& g, const std::string& name, bool instanced = false) {
  dir.write(name, g.dump());
  return renderFile(dir, name, instanced);
}

glm::dvec3 aovNormal(const Film& f, std::size_t p) {
  return glm::normalize(glm::dvec3(glm::vec3(f.aovSum[MCL_AOV_VECTORS * p + 1])));
}

// Every pixel's N AOV is `expected` (to 2e-3: the texel is stored as half floats), and `other`, the
// normal of another frame, is far from it (so the check tells the two apart).
void checkNormals(const Film& f, glm::dvec3 expected, glm::dvec3 other) {
  REQUIRE(glm::length(expected - other) > 0.1);
  for (std::size_t p = 0; p < f.pixelCount(); ++p) {
    CAPTURE(p);
    CHECK(glm::length(aovNormal(f, p) - expected) < 2e-3);
  }
}

const UvMap kMaps[] = {
    {{2 * std::cos(kPi / 6), 2 * std::sin(kPi / 6)}, {2 * std::sin(kPi / 6), -2 * std::cos(kPi / 6)}},  // rotated 30, x2
    {{1, 0}, {0, 1}},                                                                                 // mirrored UVs
};

}  // namespace

TEST_CASE("glTF TANGENT: a TANGENT equal to the UV-made frame renders the image without it, to 2 ulps" *
          doctest::test_suite("opencl")) {
  TempDir dir;
  writeNormalMap(dir);
  for (const UvMap& mp : kMaps) {
    CAPTURE(mp.du.x);
    const glm::vec4 t(uvTangent(mp));
    const Film without = renderPlane(dir, planeGltf(mp, nullptr), "without.gltf");
    const Film with = renderPlane(dir, planeGltf(mp, &t), "with.gltf");
    const glm::dvec3 tilted = mappedNormal(uvTangent(mp));
    checkNormals(without, tilted, kN);  // the map tilts the normal at all
    checkNormals(with, tilted, kN);
    // Per pixel and channel: the interpolated, re-orthogonalised file tangent and the UV-made one
    // are the same direction up to float rounding, so the radiance agrees to a few ulps.
    int exact = 0, total = 0;
    for (std::size_t p = 0; p < with.pixelCount(); ++p)
      for (int c = 0; c < 3; ++c) {
        const float a = with.meanOf(p, c), b = without.meanOf(p, c);
        REQUIRE(b > 0.0f);
        CHECK(std::fabs(a - b) <= 2.0f * std::nextafter(b, INFINITY) - 2.0f * b);
        exact += a == b, ++total;
      }
    MESSAGE(exact << " of " << total << " pixel channels bit-identical");
  }
}

TEST_CASE("glTF TANGENT: a tangent turned 90 degrees, w = -1, a mirroring and a stretching node tilt the N AOV to their own frame's mapped normal" *
          doctest::test_suite("opencl")) {
  TempDir dir;
  writeNormalMap(dir);
  for (const UvMap& mp : kMaps) {
    CAPTURE(mp.du.x);
    const glm::dvec4 t = uvTangent(mp);
    const glm::dvec3 uvMade = mappedNormal(t);
    // Turned 90 degrees about N: T' = N x T, the handedness kept.
    const glm::dvec4 turned(glm::cross(kN, glm::dvec3(t)), t.w);
    const glm::vec4 turnedF(turned);
    checkNormals(renderPlane(dir, planeGltf(mp, &turnedF), "turned.gltf"), mappedNormal(turned), uvMade);
    // The other handedness: B = -(N x T), the map's green mirrored.
    const glm::dvec4 flipped(glm::dvec3(t), -t.w);
    const glm::vec4 flippedF(flipped);
    checkNormals(renderPlane(dir, planeGltf(mp, &flippedF), "flipped.gltf"), mappedNormal(flipped), uvMade);
    // A node mirrored in x mirrors the whole relief: n' = (-n.x, n.y, n.z), with the file's frame
    // (its w flipped by the placement) as with the UVs' own; unflipped, B would point the wrong way.
    const glm::vec4 tF(t);
    const glm::dvec3 mirrored(-uvMade.x, uvMade.y, uvMade.z);
    const glm::dvec3 wrongW = mappedNormal(glm::dvec4(-t.x, t.y, t.z, t.w));
    const glm::dvec3 mirrorX(-1, 1, 1);
    checkNormals(renderPlane(dir, planeGltf(mp, nullptr, mirrorX), "mirror-uv.gltf"), mirrored, wrongW);
    checkNormals(renderPlane(dir, planeGltf(mp, &tF, mirrorX), "mirror-tangent.gltf"), mirrored, wrongW);
    // The same mirrored mesh placed twice (a two-level BVH: tangents in object space, the frame
    // placed by the instance).
    checkNormals(renderPlane(dir, planeGltf(mp, &tF, mirrorX, true), "instanced.gltf", true), mirrored, wrongW);
    // The same mirror as a scene file's mesh transform (placeTriangle, as flattened instances).
    dir.write("plane.gltf", planeGltf(mp, &tF).dump());
    dir.write("entry.json", R"({"camera": "auto", "meshes": [{"file": "plane.gltf", "transform": {"scale": [-1, 1, 1]}}]})");
    checkNormals(renderFile(dir, "entry.json"), mirrored, wrongW);
    // Stretched 2x along x: the tangent moves as a direction (M T), not as a normal (M^-T T); the
    // map whose tangent is along x cannot tell the two apart, so only the rotated one checks it.
    if (t.z != 0.0) {
      const glm::dvec3 scale(2, 1, 1);
      const glm::dvec3 asDirection = glm::normalize(scale * glm::dvec3(t)), asNormal = glm::normalize(glm::dvec3(t) / scale);
      checkNormals(renderPlane(dir, planeGltf(mp, &tF, scale), "stretched.gltf"), mappedNormal(glm::dvec4(asDirection, t.w)),
                   mappedNormal(glm::dvec4(asNormal, t.w)));
    }
  }
}

TEST_CASE("glTF TANGENT: quantized (normalized SHORT) tangents load; kHasTangents carries them placed" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  writeNormalMap(dir);
  const glm::vec4 t(0.6f, 0.0f, -0.8f, -1.0f);
  nlohmann::json g = planeGltf(kMaps[0], &t);
  // Replace the float tangents by normalized SHORTs (KHR_mesh_quantization): 0.6 -> 19660.
  std::string shorts;
  for (int k = 0; k < 4; ++k)
    for (std::int16_t c : {std::int16_t(19660), std::int16_t(0), std::int16_t(-26214), std::int16_t(-32767)})
      shorts.append(reinterpret_cast<const char*>(&c), sizeof c);
  g["buffers"].push_back({{"uri", "data:application/octet-stream;base64," + base64(shorts)}, {"byteLength", 32}});
  g["bufferViews"][3] = {{"buffer", 1}, {"byteOffset", 0}, {"byteLength", 32}};
  g["accessors"][3]["componentType"] = 5122;
  g["accessors"][3]["normalized"] = true;
  g["extensionsUsed"] = {"KHR_mesh_quantization"};
  g["extensionsRequired"] = {"KHR_mesh_quantization"};
  dir.write("q.gltf", g.dump());
  std::vector<std::string> warnings;
  const Scene s = loadScene(dir.file("q.gltf"), warnings);
  REQUIRE(s.triangles.size() == 2);
  REQUIRE(s.vertexTangents.size() == 6);
  for (const SceneTriangle& tri : s.triangles) CHECK((tri.attributes & kHasTangents) != 0);
  for (const glm::vec4& q : s.vertexTangents) {
    CHECK(q.x == doctest::Approx(0.6).epsilon(1e-4));
    CHECK(q.y == 0.0f);
    CHECK(q.z == doctest::Approx(-0.8).epsilon(1e-4));
    CHECK(q.w == -1.0f);
    CHECK(glm::length(glm::vec3(q)) == doctest::Approx(1.0).epsilon(1e-6));  // unit again
  }
}

TEST_CASE("glTF TANGENT: a wrong type, component type or count is one line naming the file and the attribute, exit 2" *
          doctest::test_suite("cli sanitize")) {
  TempDir dir;
  writeNormalMap(dir);
  const glm::vec4 t(1, 0, 0, 1);
  const nlohmann::json g = planeGltf(kMaps[0], &t);
  const struct {
    const char* file;
    const char* key;
    nlohmann::json value;
    std::string needle;
  } cases[] = {
      {"vec3.gltf", "type", "VEC3", "meshes[0].primitives[0].TANGENT: expected a VEC4 accessor"},
      {"ubyte.gltf", "componentType", 5121, "meshes[0].primitives[0].TANGENT: expected FLOAT or (KHR_mesh_quantization) normalized signed"},
      {"count.gltf", "count", 3, "meshes[0].primitives[0].TANGENT: 3 elements, POSITION has 4"},
  };
  for (const auto& c : cases) {
    CAPTURE(std::string(c.file));
    nlohmann::json bad = g;
    bad["accessors"][3][c.key] = c.value;
    dir.write(c.file, bad.dump());
    const CliResult r = runMontecl({"render", dir.file(c.file), "-o", dir.file("out.png"), "-q"});
    INFO(r.err);
    CHECK(r.exitCode == 2);
    CHECK(r.err.find(dir.file(c.file)) != std::string::npos);
    CHECK(r.err.find(c.needle) != std::string::npos);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK_FALSE(std::filesystem::exists(dir.file("out.png")));
  }
}

TEST_CASE("glTF TANGENT: the conformance set's tangent case shades by its tangents (differs from the UV-made frame)" *
          doctest::test_suite("cpu")) {
  std::vector<std::string> skipped;
  ConformanceSetOptions o;
  o.cornellPath = "/nonexistent";
  const std::vector<ConformanceCase> cases = conformanceSet(o, skipped);
  const auto render = [&](const std::string& name) {
    const auto c = std::find_if(cases.begin(), cases.end(), [&](const ConformanceCase& k) { return k.name == name; });
    REQUIRE(c != cases.end());
    WavefrontRenderer host(hostDeviceInfo(), {});
    RenderStats stats;
    RenderPart part;
    part.textures = c->textures.get();
    return host.render(c->scene, buildSceneBvh(c->scene), stats, {}, part);
  };
  const Film uv = render("normal-map/path"), file = render("normal-map/path-tangents");
  REQUIRE(uv.mean.size() == file.mean.size());
  std::size_t differ = 0;
  for (std::size_t p = 0; p < uv.mean.size(); ++p) differ += uv.mean[p] != file.mean[p];
  INFO("pixels that differ: " << differ << " of " << uv.mean.size());
  CHECK(differ >= uv.mean.size() / 4);
}

}  // namespace test_file_gltf_tangents
