// scenes.cpp: builds the conformance set (see scenes.h). Every case uses a fixed seed, so every
// backend renders the same random numbers; the scenes avoid exact ties (rays along edges) so that
// last-bit differences between devices cannot flip a visibility decision.
#include "conformance/scenes.h"

#include "conformance/layered_scene.h"
#include "scene/builtin_scenes.h"
#include "scene/mesh_entry.h"
#include "texture/bump_gradient.h"
#include "texture/mip_chain.h"

#include <cmath>
#include <fstream>

#include <glm/gtc/matrix_transform.hpp>

namespace montecl {
namespace {

// The shared wall scene with the conformance set's fixed seed.
Scene seededWallScene(int size, int spp) {
  Scene s = wallScene(size, spp);
  s.render.seed = 7;
  return s;
}

// A tilted square light (front face toward the floor) over a coloured floor, with a small
// occluding quad casting a soft shadow; seen obliquely so the image also holds the light itself.
Scene polygonLightScene(int size, int spp) {
  Scene s;
  s.path = "<polygon light scene>";
  s.materials = {MaterialDesc{"floor", glm::vec3(0.5f, 0.6f, 0.7f), glm::vec3(0.0f)},
                 MaterialDesc{"light", glm::vec3(0.0f), glm::vec3(2.0f, 3.0f, 4.0f)},
                 MaterialDesc{"occluder", glm::vec3(0.3f, 0.2f, 0.1f), glm::vec3(0.0f)}};
  addFloor(s, 0);
  // Light: a square of side 0.8 around (0.5, 1, 0.3), normal roughly (-1, -1, 0.2) normalised.
  const glm::vec3 c(0.5f, 1.0f, 0.3f), n = glm::normalize(glm::vec3(-1.0f, -1.0f, 0.2f));
  const glm::vec3 t = glm::normalize(glm::cross(n, glm::vec3(0, 1, 0))), b = glm::cross(n, t);
  const float h = 0.4f;
  std::vector<glm::vec3> v = {c - t * h - b * h, c + t * h - b * h, c + t * h + b * h, c - t * h + b * h};
  if (glm::dot(glm::cross(v[1] - v[0], v[2] - v[0]), n) < 0) std::swap(v[1], v[3]);
  addQuad(s, v[0], v[1], v[2], v[3], 1);
  // Occluder: a horizontal quad at y = 0.35 over part of the floor.
  addQuad(s, {-0.25f, 0.35f, -0.2f}, {-0.25f, 0.35f, 0.15f}, {0.1f, 0.35f, 0.15f}, {0.1f, 0.35f, -0.2f}, 2);
  s.camera.position = {-1.7f, 1.3f, 0.9f};
  s.camera.target = {0.05f, 0.2f, 0.05f};
  s.camera.fovY = 55.0f;
  s.camera.width = s.camera.height = size;
  s.render.spp = spp;
  s.render.seed = 5;
  s.render.background = {0.1f, 0.2f, 0.3f};  // the far horizon is a miss
  s.render.integrator = Integrator::Direct;
  finishScene(s);
  return s;
}

// The polygon-light scene with UVs on the floor and the occluder: the floor's albedo is Kd x an
// 8x8 checker (repeated, so the camera sees several mip levels), the occluder a cut-out of 2-texel
// stripes (alpha channel 0 or 1). Textures are packed from decoded pixels, as loadSceneTextures
// would after reading files.
ConformanceCase texturedCase(const Scene& light, const std::string& name) {
  ConformanceCase c;
  c.name = name;
  c.scene = light;
  c.scene.path = "<textured polygon light scene>";
  for (SceneTriangle& t : c.scene.triangles) {
    if (t.material != 0 && t.material != 2) continue;
    for (int k = 0; k < 3; ++k) t.uv[k] = glm::vec2(t.v[k].x, t.v[k].z) * 2.3f + glm::vec2(0.13f, 0.07f);
    t.attributes |= kHasUv;
  }
  RgbaImage checker, stripes;
  checker.width = checker.height = 8;
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x)
      checker.texels.push_back((x + y) % 2 ? glm::vec4(0.9f, 0.8f, 0.3f, 1.0f) : glm::vec4(0.1f, 0.3f, 0.6f, 1.0f));
  stripes.width = 8;
  stripes.height = 2;
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 8; ++x) stripes.texels.push_back(glm::vec4(1.0f, 1.0f, 1.0f, (x / 2) % 2 ? 1.0f : 0.0f));
  auto t = std::make_shared<SceneTextures>();
  std::vector<std::string> warnings;
  packTextures(*t, {checker, stripes}, kDefaultTextureBudget, warnings);
  t->files = {"<checker>", "<stripes>"};
  t->materials.assign(c.scene.materials.size(), MaterialTextures{});
  t->materials[0].albedo = 0;
  t->materials[2].alpha = 1;
  t->materials[2].alphaChannel = 3;
  c.textures = t;
  return c;
}

// texturedCase with the floor's checker read through a UV transform, clamped in u and mirrored in
// v, times vertex colours, under tilted corner normals: each attribute the packet stages read in
// lanes for the diffuse kind (shading normal, vertex colour, trilinear texture, wrap modes).
ConformanceCase texturedAttributesCase(const Scene& light, const std::string& name) {
  ConformanceCase c = texturedCase(light, name);
  c.scene.path = "<textured, coloured, smooth polygon light scene>";
  for (std::size_t i = 0; i < c.scene.triangles.size(); ++i) {
    SceneTriangle& t = c.scene.triangles[i];
    if (t.material != 0) continue;
    c.scene.vertexColors.resize(3 * c.scene.triangles.size(), glm::vec3(1.0f));
    for (int k = 0; k < 3; ++k) {
      t.n[k] = glm::normalize(glm::vec3(0.3f * std::sin(3.0f * t.v[k].x), 1.0f, 0.25f * std::cos(2.0f * t.v[k].z)));
      c.scene.vertexColors[3 * i + k] = glm::vec3(0.5f + 0.4f * std::sin(t.v[k].x), 0.7f, 0.4f + 0.5f * std::cos(t.v[k].z));
    }
    t.attributes |= kHasNormals | kHasColor;
  }
  auto t = std::make_shared<SceneTextures>(*c.textures);
  TextureDesc d = t->textures[0];
  d.uvRow0 = glm::vec4(0.8f, 0.3f, 0.1f, glm::uintBitsToFloat(MCL_WRAP_CLAMP));
  d.uvRow1 = glm::vec4(-0.2f, 1.1f, 0.05f, glm::uintBitsToFloat(MCL_WRAP_MIRROR));
  t->textures.push_back(d);
  t->files.push_back("<checker, transformed>");
  t->materials[0].albedo = static_cast<std::uint32_t>(t->textures.size() - 1);
  c.textures = t;
  return c;
}

// The polygon-light scene with an emission texture on the light (black but for a bright cross,
// so some of the light's triangles emit only in part) and/or a tangent-space normal map on the
// floor (decoded vectors, as scene_textures.cpp stores them) or a height map (its gradient, as
// bump_gradient.cpp makes it): the textured-emitter table and pdfs, and the mapped shading frame.
ConformanceCase lampAndBumpsCase(const Scene& light, const std::string& name, bool lamp, bool bumps,
                                 bool heights = false) {
  ConformanceCase c;
  c.name = name;
  c.scene = light;
  c.scene.path = "<textured lamp and bumps scene>";
  for (SceneTriangle& t : c.scene.triangles) {
    if (!(((bumps || heights) && t.material == 0) || (lamp && t.material == 1))) continue;
    for (int k = 0; k < 3; ++k)
      t.uv[k] = t.material == 0 ? glm::vec2(t.v[k].x, t.v[k].z) * 1.7f + glm::vec2(0.11f, 0.05f)
                                : glm::vec2(t.v[k].x + t.v[k].z, t.v[k].y) * 1.1f + glm::vec2(0.2f, 0.3f);
    t.attributes |= kHasUv;
  }
  RgbaImage cross, normals;
  cross.width = cross.height = 8;
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x)
      cross.texels.push_back(x == 3 || y == 5 ? glm::vec4(2.0f, 1.5f, 1.0f, 1.0f) : glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
  normals.width = normals.height = 4;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      const glm::vec3 n = glm::normalize(glm::vec3(0.4f * float(x - 1.5f) / 1.5f, 0.3f * float((y * 3) % 4 - 1.5f) / 1.5f, 1.0f));
      normals.texels.push_back(glm::vec4(n, 1.0f));
    }
  auto t = std::make_shared<SceneTextures>();
  std::vector<std::string> warnings;
  RgbaImage height;  // bumps of a few texels each, on a slope
  height.width = height.height = 8;
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      const float h = 0.05f * float(x) + ((x * 5 + y * 3) % 7 == 0 ? 0.3f : 0.0f);
      height.texels.push_back(glm::vec4(h, h, h, 1.0f));
    }
  packTextures(*t, {cross, normals, bumpGradient(height, 0.2f, MCL_WRAP_REPEAT, MCL_WRAP_REPEAT)}, kDefaultTextureBudget,
               warnings);
  t->files = {"<cross>", "<normals>", "<heights>"};
  t->materials.assign(c.scene.materials.size(), MaterialTextures{});
  if (lamp) t->materials[1].emission = 0;
  if (bumps) t->materials[0].normal = 1;
  if (heights) t->materials[0].bump = 2;
  c.textures = t;
  return c;
}

// The normal-mapped case c with the floor's frame from corner tangents (glTF TANGENT) instead of
// its UVs: directions that turn with position (so the interpolation matters) and a handedness that
// differs between triangles (one corner of some disagreeing: the majority rule).
ConformanceCase withFileTangents(ConformanceCase c, const std::string& name) {
  c.name = name;
  Scene& s = c.scene;
  s.vertexTangents.assign(3 * s.triangles.size(), glm::vec4(0.0f));
  for (std::size_t i = 0; i < s.triangles.size(); ++i) {
    SceneTriangle& t = s.triangles[i];
    if (t.material != 0) continue;
    t.attributes |= kHasTangents;
    for (std::size_t k = 0; k < 3; ++k) {
      const float a = 0.7f * t.v[k].x + 1.3f * t.v[k].z, w = (i + (i % 3 == 0 ? k / 2 : 0)) % 2 ? -1.0f : 1.0f;
      s.vertexTangents[3 * i + k] = glm::vec4(std::cos(a), 0.0f, std::sin(a), w);
    }
  }
  return c;
}

// The polygon-light scene with a smooth glossy sphere (object space, radius 1) placed 6 times as
// instances (turned, scaled non-uniformly, one mirrored): the two-level BVH through every device's
// kernels as the host backend runs it.
Scene instancedSpheresScene(const Scene& light) {
  Scene s = light;
  s.path = "<instanced spheres scene>";
  MaterialDesc glossy{"glossy", glm::vec3(0.6f, 0.5f, 0.3f), glm::vec3(0.0f)};
  glossy.specular = glm::vec3(0.3f);
  glossy.specularExponent = 30.0f;
  s.materials.push_back(glossy);
  const std::uint32_t first = std::uint32_t(s.triangles.size());
  addUvSphere(s, {0.0f, 0.0f, 0.0f}, 1.0f, 6, 10, true, std::uint32_t(s.materials.size() - 1));
  s.meshRanges.push_back({first, std::uint32_t(s.triangles.size()) - first});
  for (int k = 0; k < 6; ++k) {
    glm::dmat4 m = glm::translate(glm::dmat4(1.0), glm::dvec3(-0.6 + 0.25 * k, 0.2 + 0.03 * k, -0.45 + 0.17 * k));
    m = glm::rotate(m, 0.4 + 0.9 * k, glm::normalize(glm::dvec3(0.3, 1.0, 0.1 * k)));
    m = glm::scale(m, glm::dvec3(k == 3 ? -0.22 : 0.22, 0.14 + 0.02 * k, 0.2));
    s.instances.push_back({0, m});
  }
  recomputeBounds(s);
  return s;
}

Scene withAo(Scene s, AoSampling sampling) {
  s.render.integrator = Integrator::Ao;
  s.render.aoSampling = sampling;
  return s;
}

Scene withSobol(Scene s) {
  s.render.sampler = Sampler::Sobol;
  return s;
}

Scene withDirect(Scene s, DirectSampling strategy, int lightSamples) {
  s.render.integrator = Integrator::Direct;
  s.render.directSampling = strategy;
  s.render.lightSamples = lightSamples;
  return s;
}

// Path tracing, unlimited depth unless given, Russian roulette from depth 2 (so the set exercises it).
Scene withPath(Scene s, int lightSamples, int maxDepth = -1) {
  s.render.integrator = Integrator::Path;
  s.render.lightSamples = lightSamples;
  s.render.maxDepth = maxDepth;
  s.render.rrDepth = 2;
  return s;
}

}  // namespace

std::string defaultCornellPath() {
  return std::string(MONTECL_SOURCE_DIR) + "/../shared/scenes/cornell-box/scene.json";
}

std::vector<ConformanceCase> conformanceSet(const ConformanceSetOptions& o, std::vector<std::string>& skipped) {
  std::vector<ConformanceCase> cases;
  const Scene wall = seededWallScene(o.size, o.spp);
  cases.push_back({"wall/ao-uniform", withAo(wall, AoSampling::Uniform), nullptr, false});
  cases.push_back({"wall/ao-cosine", withAo(wall, AoSampling::Cosine), nullptr, false});
  Scene shortAo = withAo(wall, AoSampling::Uniform);
  shortAo.render.aoDistance = 0.3f;
  cases.push_back({"wall/ao-uniform-distance-0.3", shortAo, nullptr, false});
  const Scene light = polygonLightScene(o.size, o.spp);
  cases.push_back({"polygon-light/direct-light", withDirect(light, DirectSampling::Light, 1), nullptr, false});
  cases.push_back({"polygon-light/direct-brdf", withDirect(light, DirectSampling::Brdf, 1), nullptr, false});
  cases.push_back({"polygon-light/direct-mis", withDirect(light, DirectSampling::Mis, 2), nullptr, false});
  cases.push_back({"polygon-light/ao-cosine", withAo(light, AoSampling::Cosine), nullptr, false});
  // A row of 12 small lamps facing down beside the square (26 emitting triangles): the emitter
  // pick goes through its guide table (kernels/shared/lights.h), in the packet stages and per item.
  // The camera sees the lamps' backs: the direct case records the AOVs too (the normal AOV faces
  // the camera on untextured back faces, record_aov_lanes.h).
  Scene lamps = light;
  lamps.path = "<lamp row scene>";
  for (int i = 0; i < 12; ++i) {
    const float x = -0.6f + 0.1f * float(i), z = -0.5f + 0.02f * float(i);
    addQuad(lamps, {x, 1.2f, z}, {x + 0.05f, 1.2f, z}, {x + 0.05f, 1.2f, z + 0.05f}, {x, 1.2f, z + 0.05f}, 1);
  }
  finishScene(lamps);
  cases.push_back({"lamp-row/direct-mis-aov", withDirect(lamps, DirectSampling::Mis, 2), nullptr, true});
  cases.push_back({"lamp-row/path", withPath(lamps, 1), nullptr, false});
  // Shading normals: a coarse sphere with exact corner normals beside the occluder.
  Scene sphere = light;
  sphere.path = "<smooth sphere scene>";
  addUvSphere(sphere, {-0.4f, 0.22f, 0.45f}, 0.2f, 8, 16, true, 2);
  finishScene(sphere);
  cases.push_back({"smooth-sphere/direct-mis", withDirect(sphere, DirectSampling::Mis, 2), nullptr, false});
  cases.push_back({"smooth-sphere/ao-uniform", withAo(sphere, AoSampling::Uniform), nullptr, false});
  // The same with every material glossy, path traced: the BSDF around the shading frame.
  Scene glossySphere = sphere;
  for (MaterialDesc& m : glossySphere.materials)
    if (m.emission == glm::vec3(0.0f)) {
      m.albedo *= 0.6f;
      m.specular = glm::vec3(0.3f);
      m.specularExponent = 30.0f;
    }
  cases.push_back({"smooth-sphere/glossy-path", withPath(glossySphere, 1), nullptr, false});
  cases.push_back({"polygon-light/path", withPath(light, 2), nullptr, false});
  // Delta and glossy kinds: the smooth sphere as glass (both interfaces, shading normals), the
  // occluder a rough gold conductor (path) or a smooth mirror (direct), the floor glTF
  // metallic-roughness, under the area light and a constant environment.
  for (int direct = 0; direct < 2; ++direct) {
    Scene delta = light;
    delta.path = "<glass and metal scene>";
    addUvSphere(delta, {-0.4f, 0.22f, 0.45f}, 0.2f, 8, 16, true, 3);
    MaterialDesc glass{"glass", glm::vec3(1.0f), glm::vec3(0.0f)};
    glass.kind = MCL_MATERIAL_dielectric;
    glass.ior = 1.5f;
    delta.materials.push_back(glass);
    MaterialDesc& gold = delta.materials[2];
    gold.kind = MCL_MATERIAL_conductor;
    gold.eta = {0.143f, 0.375f, 1.442f};
    gold.k = {3.983f, 2.386f, 1.603f};
    gold.kindAlpha = direct ? 0.0f : 0.2f;
    if (!direct) {
      delta.materials[0].kind = MCL_MATERIAL_metal_rough;
      delta.materials[0].metallic = 0.3f;
      delta.materials[0].roughness = 0.5f;
    }
    delta.environment.enabled = true;
    delta.environment.radiance = {0.3f, 0.4f, 0.5f};
    finishScene(delta);
    if (direct) cases.push_back({"glass-mirror/direct-mis", withDirect(delta, DirectSampling::Mis, 2), nullptr, false});
    else cases.push_back({"glass-metal/path", withPath(delta, 1), nullptr, false});
    if (!direct) {  // the gold as Tungsten's and Mitsuba's rough metal: Beckmann, a factor on F
      Scene beckmann = delta;
      beckmann.materials[2].beckmann = true;
      beckmann.materials[2].conductorFactor = {0.8f, 0.9f, 0.3f};
      cases.push_back({"glass-metal-beckmann/path", withPath(beckmann, 1), nullptr, false});
    }
  }
  cases.push_back(texturedCase(withDirect(light, DirectSampling::Mis, 2), "textured-cutout/direct-mis"));
  cases.push_back(texturedCase(withAo(light, AoSampling::Cosine), "textured-cutout/ao-cosine"));
  cases.push_back(texturedCase(withPath(light, 1), "textured-cutout/path"));
  // Stochastic transparency (glTF BLEND): the occluder 0.6 x its stripes' alpha, the floor 0.85 by
  // its factor alone (misses behind it see the background); camera, bounce and shadow rays.
  for (ConformanceCase c : {texturedCase(withDirect(light, DirectSampling::Mis, 2), "blend/direct-mis"),
                            texturedCase(withPath(light, 1), "blend/path")}) {
    c.scene.materials[2].alphaBlend = c.scene.materials[0].alphaBlend = true;
    c.scene.materials[2].alphaFactor = 0.6f, c.scene.materials[0].alphaFactor = 0.85f;
    cases.push_back(c);
  }
  cases.push_back(texturedAttributesCase(withDirect(light, DirectSampling::Mis, 2), "textured-attributes/direct-mis"));
  cases.push_back(texturedAttributesCase(withPath(light, 1), "textured-attributes/path"));
  // First-hit AOVs (albedo through the texture, shading normal, depth, emission seen directly: the
  // background on the horizon's misses), recorded by both kinds of wave.
  for (ConformanceCase c : {texturedCase(withDirect(light, DirectSampling::Mis, 1), "textured-cutout/direct-mis-aov"),
                            texturedCase(withPath(light, 1), "textured-cutout/path-aov")}) {
    c.aovs = true;
    cases.push_back(c);
  }
  Scene lens = withPath(light, 1, 3);
  lens.camera.apertureRadius = 0.05f;
  lens.camera.focusDistance = 1.5f;
  cases.push_back({"polygon-light/path-depth-3-thin-lens", lens, nullptr, false});
  // The same scene with glossy floor and occluder (GGX lobe) under a constant environment as well.
  Scene glossy = light;
  glossy.materials[0].specular = glm::vec3(0.3f, 0.25f, 0.2f);
  glossy.materials[0].specularExponent = 60.0f;
  glossy.materials[2].specular = glm::vec3(0.5f);
  glossy.materials[2].specularExponent = 8.0f;
  glossy.environment.enabled = true;
  glossy.environment.radiance = {0.3f, 0.4f, 0.5f};
  cases.push_back({"glossy-environment/direct-light", withDirect(glossy, DirectSampling::Light, 1), nullptr, false});
  cases.push_back({"glossy-environment/direct-mis", withDirect(glossy, DirectSampling::Mis, 2), nullptr, false});
  cases.push_back({"glossy-environment/path", withPath(glossy, 2), nullptr, false});
  // The Sobol sampler: its lane form and the host's give the same bits (light samples 2: a coupled
  // and an uncoupled set; the thin lens: its own set).
  cases.push_back({"polygon-light/ao-uniform-sobol", withSobol(withAo(light, AoSampling::Uniform)), nullptr, false});
  cases.push_back({"polygon-light/direct-mis-sobol", withSobol(withDirect(light, DirectSampling::Mis, 2)), nullptr, false});
  cases.push_back({"glossy-environment/path-sobol", withSobol(withPath(glossy, 2)), nullptr, false});
  cases.push_back({"polygon-light/path-depth-3-thin-lens-sobol", withSobol(lens), nullptr, false});
  // The polygon light with a point, a spot and a directional light beside it (light selection
  // across kinds by power; delta lights by next-event estimation only).
  Scene punctual = light;
  LightDesc point, spot, sun;
  point.position = {-0.3f, 0.9f, 0.5f};
  point.color = {0.4f, 0.3f, 0.2f};
  spot.kind = PunctualKind::Spot;
  spot.position = {0.2f, 1.2f, -0.4f};
  spot.direction = glm::normalize(glm::vec3(-0.2f, -1.0f, 0.3f));
  spot.color = {1.5f, 1.0f, 0.5f};
  spot.cutoffDegrees = 35.0f;
  spot.beamDegrees = 20.0f;
  sun.kind = PunctualKind::Directional;
  sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, -0.2f));
  sun.color = {0.2f, 0.25f, 0.3f};
  punctual.lights = {point, spot, sun};
  cases.push_back({"punctual-lights/direct-mis", withDirect(punctual, DirectSampling::Mis, 2), nullptr, false});
  cases.push_back({"punctual-lights/path", withPath(punctual, 2), nullptr, false});
  Scene onlyPoint = light;
  onlyPoint.materials[1].emission = glm::vec3(0.0f);  // the quad no longer emits: the point light alone
  onlyPoint.lights = {point};
  cases.push_back({"point-light/path", withPath(onlyPoint, 1), nullptr, false});
  // The sun (a disk sampled by solid angle) beside the polygon light.
  Scene sunLit = light;
  LightDesc disk;
  disk.kind = PunctualKind::Sun;
  disk.direction = glm::normalize(glm::vec3(-0.4f, -1.0f, 0.3f));
  disk.color = {0.6f, 0.5f, 0.4f};
  disk.angleDegrees = 6.0f;
  sunLit.lights = {disk};
  cases.push_back({"sun/direct-mis", withDirect(sunLit, DirectSampling::Mis, 2), nullptr, false});
  cases.push_back({"sun/path", withPath(sunLit, 1), nullptr, false});
  // Rough glass (GGX transmission) on the smooth sphere, the occluder a partly transmissive
  // metal_rough (glTF transmission: the per-hit choice between two kinds), under the environment.
  Scene rough = light;
  rough.path = "<rough glass scene>";
  addUvSphere(rough, {-0.4f, 0.22f, 0.45f}, 0.2f, 8, 16, true, 3);
  MaterialDesc roughGlass{"rough glass", glm::vec3(1.0f), glm::vec3(0.0f)};
  roughGlass.kind = MCL_MATERIAL_dielectric;
  roughGlass.ior = 1.5f;
  roughGlass.kindAlpha = 0.3f;
  rough.materials.push_back(roughGlass);
  MaterialDesc& partly = rough.materials[2];
  partly.kind = MCL_MATERIAL_metal_rough;
  partly.metallic = 0.2f;
  partly.roughness = 0.4f;
  partly.transmission = 0.6f;
  partly.transmissionSolid = true;
  rough.environment.enabled = true;
  rough.environment.radiance = {0.3f, 0.4f, 0.5f};
  finishScene(rough);
  cases.push_back({"rough-glass/direct-mis", withDirect(rough, DirectSampling::Mis, 2), nullptr, false});
  cases.push_back({"rough-glass/path", withPath(rough, 1), nullptr, false});
  const Scene coated = layeredScene(rough);
  cases.push_back({"coated/direct-mis", withDirect(coated, DirectSampling::Mis, 2), nullptr, false});
  cases.push_back({"coated/path", withPath(coated, 1), nullptr, false});
  cases.push_back(lampAndBumpsCase(withDirect(light, DirectSampling::Mis, 2), "emissive-texture/direct-mis", true, false));
  cases.push_back(lampAndBumpsCase(withPath(light, 1), "emissive-texture/path", true, false));
  cases.push_back(lampAndBumpsCase(withDirect(light, DirectSampling::Mis, 2), "normal-map/direct-mis", false, true));
  cases.push_back(lampAndBumpsCase(withPath(light, 1), "normal-map/path", false, true));
  cases.push_back(withFileTangents(lampAndBumpsCase(withPath(light, 1), "", false, true), "normal-map/path-tangents"));
  cases.push_back(lampAndBumpsCase(withDirect(light, DirectSampling::Mis, 2), "bump-map/direct-mis", false, false, true));
  cases.push_back(lampAndBumpsCase(withPath(light, 1), "bump-map/path", false, false, true));
  const Scene spheres = instancedSpheresScene(light);
  cases.push_back({"instanced-spheres/ao-cosine", withAo(spheres, AoSampling::Cosine), nullptr, false});
  cases.push_back({"instanced-spheres/direct-mis", withDirect(spheres, DirectSampling::Mis, 2), nullptr, false});
  cases.push_back({"instanced-spheres/path", withPath(spheres, 1), nullptr, false});
  Scene blendSpheres = withPath(spheres, 1);  // BLEND spheres: the coin in each instance's object space
  blendSpheres.materials.back().alphaBlend = true, blendSpheres.materials.back().alphaFactor = 0.5f;
  cases.push_back({"instanced-spheres/path-blend", blendSpheres, nullptr, false});

  const std::string path = o.cornellPath.empty() ? defaultCornellPath() : o.cornellPath;
  if (!std::ifstream(path)) {
    skipped.push_back("cornell-box: " + path + " not found (the shared scenes are not beside this checkout)");
    return cases;
  }
  std::vector<std::string> warnings;
  Scene cornell = loadScene(path, warnings);
  cornell.camera.width = cornell.camera.height = o.cornellSize;
  cornell.render.spp = o.cornellSpp;
  cornell.render.seed = 9;
  cases.push_back({"cornell-box/direct-light", withDirect(cornell, DirectSampling::Light, 1), nullptr, false});
  cases.push_back({"cornell-box/direct-mis", withDirect(cornell, DirectSampling::Mis, 1), nullptr, false});
  cases.push_back({"cornell-box/ao-cosine", withAo(cornell, AoSampling::Cosine), nullptr, false});
  cases.push_back({"cornell-box/path", withPath(cornell, 1), nullptr, false});
  cases.push_back({"cornell-box/direct-mis-sobol", withSobol(withDirect(cornell, DirectSampling::Mis, 1)), nullptr, false});
  cases.push_back({"cornell-box/path-sobol", withSobol(withPath(cornell, 1)), nullptr, false});
  return cases;
}

}  // namespace montecl
