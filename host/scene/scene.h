// scene.h: the in-memory scene: camera, triangle soup with per-triangle materials, render settings.
// Filled by loadScene() from a scene file (JSON) or a bare OBJ; consumed by the BVH and renderer.
#pragma once
#include <glm/glm.hpp>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "kernels/shared/material_kinds.h"
#include "scene/render_settings.h"

namespace montecl {

struct Camera {
  glm::vec3 position{0.0f, 0.0f, 1.0f};
  glm::vec3 target{0.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  float fovY = 45.0f;  // full vertical field of view, degrees, in (0, 180)
  int width = 512;
  int height = 512;
  float apertureRadius = 0.0f;  // thin lens radius ("aperture_radius"), 0: pinhole
  float focusDistance = 0.0f;   // distance of the plane in focus ("focus_distance"); 0: |target - position|
};

// How one texture of a material is read (glTF KHR_texture_transform and the sampler's wrap
// modes): the affine map from the surface's UVs to the texture's (both in montecl's convention,
// v up; u' = row0 . (u, v, 1), v' = row1 . (u, v, 1)) and a wrap mode per axis (MCL_WRAP_*:
// 0 repeat, 1 clamp to edge, 2 mirrored repeat). The default reads the texture as it always was.
struct TextureSampling {
  glm::vec3 row0{1.0f, 0.0f, 0.0f}, row1{0.0f, 1.0f, 0.0f};
  std::uint32_t wrapS = 0, wrapT = 0;
  bool identity() const {
    return row0 == glm::vec3(1.0f, 0.0f, 0.0f) && row1 == glm::vec3(0.0f, 1.0f, 0.0f) && wrapS == 0 && wrapT == 0;
  }
};

struct MaterialDesc {
  MaterialDesc() = default;
  MaterialDesc(std::string name_, glm::vec3 albedo_, glm::vec3 emission_ = glm::vec3(0.0f))
      : name(std::move(name_)), albedo(albedo_), emission(emission_) {}
  std::string name;
  std::uint32_t kind = MCL_MATERIAL_diffuse;  // MCL_MATERIAL_<kind> (kernels/shared/material_kinds.h)
  glm::vec3 albedo{0.5f};    // Kd (multiplies albedoTexture when there is one)
  glm::vec3 emission{0.0f};  // Ke
  bool twoSidedEmission = false;  // both faces emit Ke (scene key "two_sided_emission"), else the front only
  // Textures: paths as opened (resolved against the file that named them); empty = none. Texture
  // coordinates everywhere follow OBJ's convention (v = 0 at the image's bottom row): loaders of
  // top-origin formats (glTF) flip v when they read it.
  std::string albedoTexture;  // map_Kd, glTF baseColorTexture (8-bit: sRGB-encoded)
  std::string alphaTexture;   // map_d, or the albedo texture's alpha (glTF MASK); empty: opaque
  std::string emissionTexture;  // map_Ke, glTF emissiveTexture (colour, like the albedo's): Le = Ke x it
  float alphaCutoff = 0.5f;   // a hit whose alpha is below this does not exist for any ray
  // Stochastic transparency (glTF alphaMode BLEND) in place of the cut-out: a ray meets the surface
  // with probability alphaFactor x the alpha texture's alpha there (1 without one) and passes
  // through otherwise (alphaCutoff unused), decided by a hash of the ray and the triangle
  // (kernels/shared/surface_texture.h alpha_hit_exists).
  bool alphaBlend = false;
  float alphaFactor = 1.0f;   // in [0, 1]; glTF: baseColorFactor's alpha
  // Tangent-space normal map (glTF normalTexture, MTL norm; read linear, never sRGB-decoded):
  // n = ((2r - 1) normalScale, (2g - 1) normalScale, 2b - 1) in the triangle's UV tangent frame.
  std::string normalTexture;
  float normalScale = 1.0f;
  // Height-map bump mapping (MTL bump / map_Bump / map_bump; linear, the mean of R, G, B): the
  // surface displaced by bumpScale (-bm) x height along the shading normal (bump_map.h). A material
  // with a normal map ignores it (the MTL loader drops it with a warning).
  std::string bumpTexture;
  float bumpScale = 1.0f;
  glm::vec3 specular{0.0f};   // Ks (the GGX glossy lobe), 0: Lambertian only
  float specularExponent = 0.0f;  // Ns
  // The kinds' own parameters (scene keys, host/scene/material_params.cpp; docs/scene-format.md);
  // read only by their kind (deviceMaterial packs them into Material::params0/1).
  glm::vec3 eta{0.0f}, k{1.0f};  // conductor: complex IOR (default eta 0, k 1: a perfect mirror)
  float ior = 1.5f;               // dielectric, thin_dielectric: inside / outside
  float kindAlpha = 0.0f;         // conductor, dielectric: GGX alpha (0: smooth)
  // conductor: Beckmann microfacets of alpha kindAlpha in place of GGX (Mitsuba's and Tungsten's
  // default distribution), and a factor on its Fresnel term (Mitsuba's specular_reflectance,
  // Tungsten's albedo).
  bool beckmann = false;
  glm::vec3 conductorFactor{1.0f};
  float metallic = 0.0f, roughness = 1.0f;  // metal_rough (glTF factors)
  // coated_diffuse (pbrt-v4's layered coat over a Lambertian base of reflectance `albedo`; the coat
  // is a dielectric of index `ior`, GGX `kindAlpha`): the thickness of the clear layer between the
  // interface and the base (it attenuates as exp(-thickness / |cos|), as pbrt's), and the random
  // walk's bounce limit and its walks per evaluation.
  float thickness = 0.01f;
  int layerMaxDepth = 10, layerSamples = 1;
  // coated_conductor: the same coat and layer over a conductor of index eta + i k (the metal's own,
  // relative to vacuum: the BSDF divides it by ior) and GGX alpha baseAlpha (0: smooth).
  float baseAlpha = 0.0f;
  std::string metallicRoughnessTexture;  // glTF metallicRoughnessTexture (linear; B x metallic, G x roughness)
  // When specGlossMap, metallicRoughnessTexture is a glTF specular-glossiness map
  // (KHR_materials_pbrSpecularGlossiness's specularGlossinessTexture: sRGB specular colour, linear
  // glossiness in alpha), which the texture loader converts texel by texel to (0, roughness,
  // metallic) through metalRoughFromSpecGloss (scene/gltf_spec_gloss.h) with specular = texel x
  // specGloss.rgb, glossiness = alpha x specGloss.w and the diffuse colour specGlossDiffuse.
  bool specGlossMap = false;
  glm::vec4 specGloss{1.0f};
  glm::vec3 specGlossDiffuse{1.0f};
  // metal_rough: glTF KHR_materials_transmission's factor (0: none) through a dielectric of index
  // `ior`, solid (KHR_materials_volume) or a thin sheet (kernels/shared/transmission_mix.h).
  float transmission = 0.0f;
  bool transmissionSolid = false;
  // glTF transmissionTexture (linear; R x transmission, per hit), read where transmission > 0.
  std::string transmissionTexture;
  TextureSampling transmissionSampling;
  // dielectric, thin_dielectric: the transmitted light is tinted by the albedo (x its texture x the
  // vertex colours), as glTF's base colour tints its BTDF (kernels/shared/transmission_tint.h);
  // false: clear glass (the scene file's). metal_rough's transmission is always tinted so.
  bool transmissionTinted = false;
  // metal_rough: glTF KHR_materials_clearcoat's layer (factor 0: none; roughness: glTF's, alpha its
  // square), IOR 1.5 (kernels/shared/bsdf_metal_rough.h).
  float clearcoat = 0.0f, clearcoatRoughness = 0.0f;
  // metal_rough: glTF KHR_materials_sheen's layer under the coat (colour 0: none; roughness: glTF's,
  // alpha its square; kernels/shared/sheen.h).
  glm::vec3 sheenColor = glm::vec3(0.0f);
  float sheenRoughness = 0.0f;
  // An MTL map_Kd without map_d: where it is ("<mtl>: line N: material 'm': map_Kd 'name'"), so the
  // texture loader can say how to cut it out when its alpha is not all 1 (it renders opaque). "": none.
  std::string cutoutHint;
  // How each texture above is read (identity and repeat unless a glTF file says otherwise).
  TextureSampling albedoSampling, alphaSampling, emissionSampling, metallicRoughnessSampling, normalSampling,
      bumpSampling;
};

// Per-corner attributes of a triangle (SceneTriangle::attributes says which are present).
constexpr std::uint8_t kHasNormals = 1;  // n[] holds the file's vertex normals (unit length)
constexpr std::uint8_t kHasUv = 2;       // uv[] holds texture coordinates
// Scene::vertexColors[3 k ..] hold triangle k's corner colours (glTF COLOR_0, linear rgb) (8:
// MCL_ATTR_COLOR, past the device's MCL_ATTR_ALPHA 4, which loaders never set).
constexpr std::uint8_t kHasColor = 8;
// Scene::vertexTangents[3 k ..] hold triangle k's corner tangents (glTF TANGENT: xyz unit, w the
// handedness +1 or -1, placed as the triangle is) (16: MCL_ATTR_TANGENTS).
constexpr std::uint8_t kHasTangents = 16;

// A run of Scene::triangles in object space, and one placement of such a run (column vectors:
// p_world = objectToWorld * p_object; invertible, finite, affine).
struct MeshRange {
  std::uint32_t firstTri = 0, count = 0;
};
struct SceneInstance {
  std::uint32_t range = 0;
  glm::dmat4 objectToWorld{1.0};
};

struct SceneTriangle {
  glm::vec3 v[3];
  std::uint32_t material;  // index into Scene::materials
  glm::vec3 n[3]{};        // shading normals per corner (kHasNormals), already transformed
  glm::vec2 uv[3]{};       // texture coordinates per corner (kHasUv)
  std::uint8_t attributes = 0;
};

// The environment light (scene key "environment", host/scene/environment_key.cpp): radiance from
// infinitely far away, seen by camera rays that miss and lighting the scene (direct, path).
struct EnvironmentDesc {
  bool enabled = false;
  glm::vec3 radiance{1.0f};  // "radiance": the constant, or the tint multiplying the map
  std::string file;          // "file": latitude-longitude map (resolved path); empty: constant
  float scale = 1.0f;        // "scale" (>= 0): multiplies the radiance
  float rotateYDegrees = 0.0f;  // "rotate_y": rotation of the map about +y
  // A pbrt-v4 infinite light's map (host/scene/equal_area.h): a square equal-area octahedral
  // image, looked up in the direction mapFromWorld * (the escaping ray's); resampled to
  // latitude-longitude when the environment is built. False: the map is latitude-longitude.
  bool equalArea = false;
  glm::dmat3 mapFromWorld{1.0};
};

// A light that is not a triangle (scene key "lights", host/scene/lights_key.cpp; kinds in
// kernels/shared/light_kinds.h). Radiometric units: W/sr, W/m^2.
enum class PunctualKind { Point, Spot, Directional, Sun };
struct LightDesc {
  PunctualKind kind = PunctualKind::Point;
  glm::vec3 position{0.0f};           // point, spot
  glm::vec3 direction{0.0f, 0.0f, -1.0f};  // unit: the way the light travels (spot: its axis)
  glm::vec3 color{1.0f};              // intensity (point, spot) or irradiance (directional, sun)
  float cutoffDegrees = 20.0f;        // spot: no light beyond this angle from the axis
  float beamDegrees = 15.0f;          // spot: full intensity within this angle
  float angleDegrees = 0.53f;         // sun: angular diameter of its disk, in (0, 180)
};

// A texture file a loader could not open (in any case of its name): its material renders without
// it (the factor alone) when render.missing_textures is warn. A listing starts
// "<file>: <where>: <lead>" and names the later ones by "[<file> ]<brief>".
struct MissingTexture {
  std::string file, where, lead, brief;
};

struct Scene {
  std::string path;  // the file it was loaded from
  std::vector<std::string> inputFiles;  // every file read: scene file, meshes, MTLs, buffers, textures (as opened)
  Camera camera;
  RenderSettings render;
  EnvironmentDesc environment;
  std::vector<LightDesc> lights;  // point, spot, directional (lit integrators only)
  std::vector<MaterialDesc> materials;
  std::vector<SceneTriangle> triangles;  // non-degenerate triangles only
  // Corner colours of the triangles with kHasColor, 3 per triangle index (white or absent for the
  // others: the vector may be shorter than 3 x triangles); empty when none has any.
  std::vector<glm::vec3> vertexColors;
  // Corner tangents of the triangles with kHasTangents, 3 per triangle index (zero or absent for
  // the others, as vertexColors); empty when none has any, so other scenes pay nothing for them.
  std::vector<glm::vec4> vertexTangents;
  // Images held inside an input file (a .glb's bufferViews, data URIs), encoded as stored, by the
  // name a material's texture path gives them ("<file>#images[i].<ext>"; never a real file): the
  // texture loader decodes them from memory and the scene digest hashes these bytes.
  std::map<std::string, std::vector<unsigned char>> embeddedImages;
  std::vector<MissingTexture> missingTextures;  // textures left out, in the order met
  // Set by loadScene: the loaders only record missing textures, and loadScene reports every one of
  // the scene at the end (one error or one warning); else a loader fails on its file's ones (error).
  bool deferMissingTextures = false;
  std::size_t degenerateDropped = 0;     // zero-area triangles removed while loading
  std::string defaultsNote;              // a bare model's environment and why (applyBareModelDefaults), for -v
  // A bare model's own cameras (glTF perspective cameras, in the order the node walk meets them;
  // the first is `camera`): what `render --camera N` picks from.
  std::vector<Camera> fileCameras;
  // A glTF model's scenes[] count and the one loaded (render --scene N; default the file's "scene").
  std::size_t fileScenes = 0, fileScene = 0;
  glm::vec3 boundsMin{0.0f}, boundsMax{0.0f};  // world bounds (instances by their placed boxes)
  // Instanced geometry, kept unflattened (scene_instances.h): meshRanges[r] is a run of
  // `triangles` in the mesh's own (object) space, placed once per entry of `instances` naming it;
  // every triangle outside the ranges is in world space. Both empty: every triangle is world space.
  std::vector<MeshRange> meshRanges;
  std::vector<SceneInstance> instances;
};

// Loads a scene file (.json) or a bare mesh (.obj, .ply, .gltf, .glb: framed by defaultCamera()
// unless a glTF brings a camera; scene-file meshes dispatch on the same extensions). Throws InputError
// with one line "<file>: <key or line>: <problem>" for any bad input; unknown JSON keys are
// appended to warnings ("<file>: <key>: unknown key, ignored"). Texture files that cannot be opened
// follow render.missing_textures (`missing`, the command line's, replaces the scene file's): error
// throws one line listing all of them; warn leaves each out and warns once listing all.
// gltfScene (the command line's --scene) picks one of a bare glTF model's scenes; with any other
// file it is InputError "--scene: ...".
Scene loadScene(const std::string& path, std::vector<std::string>& warnings,
                std::optional<MissingTextures> missing = std::nullopt, std::optional<unsigned> gltfScene = std::nullopt);

// What a bare mesh (a model file given without a scene file) renders with, the one rule for it:
// integrator path, and a constant white sky: radiance kDefaultSkyRadiance (a diffuse surface open
// to all of it shows its albedo) when the model has no light of its own, kLitModelSkyRadiance when
// it has (an untextured emitting material or a glTF punctual light). Lights a model brings are
// mostly decorative (a lamp's bulb, a car's headlights): without any sky such a model rendered
// black but for them; a dimmer sky shows the model and leaves its lights reading as lights, as
// Blender keeps its world and glTF viewers their room environment. Textured emission (a helmet's
// lamps, a screen) keeps the full sky. The command line's --integrator and --env (none: no sky)
// replace these; Scene::defaultsNote says which was chosen (printed with -v).
constexpr float kDefaultSkyRadiance = 1.0f;
constexpr float kLitModelSkyRadiance = 0.25f;
void applyBareModelDefaults(Scene& scene);

// Appends the triangles and materials of one OBJ (+ its MTL) to scene, drops degenerate triangles
// (counted in degenerateDropped) and grows the bounds. Throws InputError "<obj>: line N: <problem>".
// Non-fatal problems (missing MTL, unknown statements) are appended to warnings when given.
void loadObjInto(const std::string& objPath, Scene& scene,
                 std::vector<std::string>* warnings = nullptr);

// Index of the scene's one shared default material (albedo 0.5 grey, no emission), added to
// scene.materials on first use. Faces without a material use it.
std::uint32_t defaultMaterialIndex(Scene& scene);

// False when the scene has emitters and non-emitting geometry but no emitter's emitting side
// (the front, or either face with twoSidedEmission) faces any of that geometry: a direct render
// is then black but for the emitters themselves. Exact for small scenes, bounding-box based above.
bool emittersFaceAnything(const Scene& scene);

// A camera looking at the bounding box from one side, framing all of it: view "front" (the +z side,
// tilted down a little; what a bare mesh gets), "back", "left" (-x), "right", "top", "bottom" or
// "iso" (from the +x +y +z corner); an unknown name is "front" (check with isViewName).
Camera defaultCamera(const glm::vec3& boundsMin, const glm::vec3& boundsMax, int width, int height,
                     const std::string& view = "front");
bool isViewName(const std::string& view);
const char* viewNames();  // "front, back, ...", for messages

}  // namespace montecl
