// test_pbrt_parser.cpp: the pbrt-v4 reader (host/scene/pbrt_*.cpp) on small inline scene files:
// pbrt's transform order, LookAt, the camera's handedness and its fov on the shorter axis, the
// depth conversion, shapes and their sides, materials, instances, Include, and that bad input is
// one "file:line:column" error while unsupported input is a file:line warning.
#include <doctest/doctest.h>

#include <glm/glm.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "skip.h"
#include "mesh_files.h"
#include "scene/camera_basis.h"
#include "scene/equal_area.h"
#include "scene/mesh_loaders.h"
#include "scene/pbrt_shapes.h"
#include "scene/scene.h"
#include "util/errors.h"

namespace test_file_pbrt_parser {  // keeps this file's helpers apart in a unity batch

using montecl::Scene;
using montecl_test::TempDir;

namespace {

// pbrt's camera space is left-handed; with the Scale -1 1 1 in front (as pbrt-v3 exporters wrote
// it) the camera mirrors already and the reader leaves the world as it is (no reflection for
// montecl's right-handed camera), so the world coordinates below are the file's.
#define MCL_PBRT_FILM                                                              \
  "Film \"rgb\" \"integer xresolution\" [ 32 ] \"integer yresolution\" [ 32 ]\n" \
  "Camera \"perspective\" \"float fov\" [ 40 ]\n"
const char* kFilm = MCL_PBRT_FILM;
const char* kCamera = "Scale -1 1 1\n" MCL_PBRT_FILM;

// One triangle (0,0,0) (1,0,0) (0,1,0), front +z.
const char* kTriangle = "Shape \"trianglemesh\" \"point3 P\" [ 0 0 0  1 0 0  0 1 0 ] \"integer indices\" [ 0 1 2 ]\n";

Scene load(const TempDir& dir, const std::string& text, std::vector<std::string>* warningsOut = nullptr) {
  dir.write("s.pbrt", text);
  std::vector<std::string> warnings;
  Scene s = montecl::loadScene(dir.file("s.pbrt"), warnings);
  if (warningsOut) *warningsOut = warnings;
  return s;
}

std::string loadError(const TempDir& dir, const std::string& text) {
  dir.write("s.pbrt", text);
  std::vector<std::string> warnings;
  try {
    montecl::loadScene(dir.file("s.pbrt"), warnings);
  } catch (const montecl::InputError& e) {
    return e.what();
  }
  return "";
}

bool near(const glm::vec3& a, const glm::vec3& b, float eps = 1e-5f) { return glm::length(a - b) <= eps; }

glm::vec3 front(const montecl::SceneTriangle& t) { return glm::normalize(glm::cross(t.v[1] - t.v[0], t.v[2] - t.v[0])); }

bool anyContains(const std::vector<std::string>& lines, const std::string& a, const std::string& b = "") {
  for (const std::string& l : lines)
    if (l.find(a) != std::string::npos && l.find(b) != std::string::npos) return true;
  return false;
}

}  // namespace

TEST_CASE("pbrt: transforms compose as pbrt's (the last one given applies first)" * doctest::test_suite("cpu pbrt")) {
  TempDir dir;
  // Translate then Scale: p' = T (S p), so (1, 0, 0) goes to (2 + 1, 0, 0); the other order gives 4.
  Scene s = load(dir, std::string(kCamera) + "WorldBegin\nTranslate 1 0 0\nScale 2 2 2\n" + kTriangle);
  REQUIRE(s.triangles.size() == 1);
  CHECK(near(s.triangles[0].v[0], glm::vec3(1, 0, 0)));
  CHECK(near(s.triangles[0].v[1], glm::vec3(3, 0, 0)));
  CHECK(near(s.triangles[0].v[2], glm::vec3(1, 2, 0)));
  // Rotate 90 about z turns +x into +y (right-handed, as pbrt's Rotate).
  s = load(dir, std::string(kCamera) + "WorldBegin\nRotate 90 0 0 1\n" + kTriangle);
  CHECK(near(s.triangles[0].v[1], glm::vec3(0, 1, 0)));
  // Transform lists the matrix column by column: the translation is in values 12..14;
  // ConcatTransform multiplies on the right; AttributeEnd restores; Identity resets.
  s = load(dir, std::string(kCamera) + "WorldBegin\nTransform [ 1 0 0 0 0 1 0 0 0 0 1 0 5 6 7 1 ]\n"
                "AttributeBegin\nConcatTransform [ 2 0 0 0 0 2 0 0 0 0 2 0 0 0 0 1 ]\n" + kTriangle +
                "AttributeEnd\n" + kTriangle + "Identity\n" + kTriangle);
  REQUIRE(s.triangles.size() == 3);
  CHECK(near(s.triangles[0].v[1], glm::vec3(7, 6, 7)));
  CHECK(near(s.triangles[1].v[1], glm::vec3(6, 6, 7)));
  CHECK(near(s.triangles[2].v[1], glm::vec3(1, 0, 0)));
  // CoordinateSystem / CoordSysTransform, and TransformBegin/End keep only the CTM.
  s = load(dir, std::string(kCamera) + "WorldBegin\nTranslate 0 0 3\nCoordinateSystem \"lifted\"\nIdentity\n"
                "TransformBegin\nScale 5 5 5\nTransformEnd\nCoordSysTransform \"lifted\"\n" + kTriangle);
  CHECK(near(s.triangles[0].v[1], glm::vec3(1, 0, 3)));
}

TEST_CASE("pbrt: a Transform camera keeps its numbers; fov spans the shorter image axis" * doctest::test_suite("cpu pbrt")) {
  TempDir dir;
  // The Bitterli Cornell box's camera: world-to-camera with z negated, camera at (0, 1, 6.8).
  const std::string cam = "Transform [ 1 -0 -0 -0 -0 1 -0 -0 -0 -0 -1 -0 -0 -1 6.8 1 ]\n";
  Scene s = load(dir, cam + "Film \"rgb\" \"integer xresolution\" [ 200 ] \"integer yresolution\" [ 100 ]\n"
                          "Camera \"perspective\" \"float fov\" [ 30 ]\nWorldBegin\n" + kTriangle);
  CHECK(near(s.camera.position, glm::vec3(0, 1, 6.8f)));
  CHECK(near(glm::normalize(s.camera.target - s.camera.position), glm::vec3(0, 0, -1)));
  CHECK(s.camera.width == 200);
  CHECK(s.camera.height == 100);
  CHECK(s.camera.fovY == doctest::Approx(30.0));  // landscape: the shorter axis is the vertical one
  CHECK(near(s.triangles[0].v[1], glm::vec3(1, 0, 0)));  // this camera needs no mirror: the world stays
  // Portrait: pbrt's fov is horizontal; montecl's vertical fov is wider.
  s = load(dir, cam + "Film \"rgb\" \"integer xresolution\" [ 100 ] \"integer yresolution\" [ 200 ]\n"
                      "Camera \"perspective\" \"float fov\" [ 30 ]\nWorldBegin\n" + kTriangle);
  const double expect = 2.0 * std::atan(std::tan(15.0 * M_PI / 180.0) * 2.0) * 180.0 / M_PI;
  CHECK(s.camera.fovY == doctest::Approx(expect).epsilon(1e-5));
  // Lens: lensradius and focaldistance.
  s = load(dir, cam + "Camera \"perspective\" \"float lensradius\" [ 0.1 ] \"float focaldistance\" [ 4 ]\nWorldBegin\n" + kTriangle);
  CHECK(s.camera.apertureRadius == doctest::Approx(0.1));
  CHECK(s.camera.focusDistance == doctest::Approx(4.0));
}

TEST_CASE("pbrt: a LookAt camera shows pbrt's picture, not its mirror image" * doctest::test_suite("cpu pbrt")) {
  TempDir dir;
  // pbrt's LookAt camera space is left-handed: from +z looking at the origin with y up, pbrt's image
  // right is world -x. The triangle at x < 0 must come out on montecl's image right.
  Scene s = load(dir, "LookAt 0 0 5  0 0 0  0 1 0\n" + std::string(kFilm) +
                          "WorldBegin\nShape \"trianglemesh\" \"point3 P\" [ -2 0 0  -1 0 0  -1 1 0 ] \"integer indices\" [ 0 1 2 ]\n");
  REQUIRE(s.triangles.size() == 1);
  CHECK(near(s.camera.position, glm::vec3(0, 0, 5)));
  const montecl::CameraBasis b = montecl::cameraBasis(s.camera);
  const glm::vec3 centre = (s.triangles[0].v[0] + s.triangles[0].v[1] + s.triangles[0].v[2]) / 3.0f;
  CHECK(glm::dot(centre - s.camera.position, b.right) > 0.5f);
  // The triangle's front (+z in pbrt, towards the camera) still faces the camera after the mirror.
  CHECK(glm::dot(front(s.triangles[0]), s.camera.position - centre) > 0.0f);
  // With pbrt-v3 exporters' Scale -1 1 1 in front of LookAt, pbrt's image right is world +x.
  s = load(dir, "Scale -1 1 1\nLookAt 0 0 5  0 0 0  0 1 0\n" + std::string(kFilm) +
                    "WorldBegin\nShape \"trianglemesh\" \"point3 P\" [ -2 0 0  -1 0 0  -1 1 0 ] \"integer indices\" [ 0 1 2 ]\n");
  const montecl::CameraBasis b2 = montecl::cameraBasis(s.camera);
  const glm::vec3 c2 = (s.triangles[0].v[0] + s.triangles[0].v[1] + s.triangles[0].v[2]) / 3.0f;
  CHECK(glm::dot(c2 - s.camera.position, b2.right) < -0.5f);
}

TEST_CASE("pbrt: Integrator maxdepth, Sampler pixelsamples and other integrators" * doctest::test_suite("cpu pbrt")) {
  TempDir dir;
  std::vector<std::string> warnings;
  // pbrt's maxdepth counts bounces (1: direct light), montecl's max_depth path segments (2: direct).
  Scene s = load(dir, "Integrator \"path\" \"integer maxdepth\" [ 1 ]\nSampler \"independent\" \"integer pixelsamples\" [ 7 ]\n" +
                          std::string(kCamera) + "WorldBegin\n" + kTriangle, &warnings);
  CHECK(s.render.integrator == montecl::Integrator::Path);
  CHECK(s.render.maxDepth == 2);
  CHECK(s.render.spp == 7);
  CHECK(s.render.sampler == montecl::Sampler::Independent);
  CHECK(warnings.empty());
  s = load(dir, std::string(kCamera) + "WorldBegin\n" + kTriangle);  // pbrt's defaults: volpath, maxdepth 5, 16 spp
  CHECK(s.render.maxDepth == 6);
  CHECK(s.render.spp == 16);
  s = load(dir, "Integrator \"bdpt\" \"integer maxdepth\" [ 9 ]\n" + std::string(kCamera) + "WorldBegin\n" + kTriangle, &warnings);
  CHECK(s.render.integrator == montecl::Integrator::Path);
  CHECK(s.render.maxDepth == 10);
  CHECK(warnings.size() == 1);
  CHECK(anyContains(warnings, "s.pbrt:1:1", "bdpt"));
}

TEST_CASE("pbrt: trianglemesh normals and ReverseOrientation decide the emitting side" * doctest::test_suite("cpu pbrt")) {
  TempDir dir;
  const std::string light = "AreaLightSource \"diffuse\" \"rgb L\" [ 2 3 4 ]\n";
  // Without N the front is the corners' cross product (+z); ReverseOrientation turns it.
  Scene s = load(dir, std::string(kCamera) + "WorldBegin\nAttributeBegin\n" + light + kTriangle +
                          "ReverseOrientation\n" + kTriangle + "AttributeEnd\n" + kTriangle);
  REQUIRE(s.triangles.size() == 3);
  CHECK(near(front(s.triangles[0]), glm::vec3(0, 0, 1)));
  CHECK(near(front(s.triangles[1]), glm::vec3(0, 0, -1)));
  CHECK(near(front(s.triangles[2]), glm::vec3(0, 0, 1)));
  const montecl::MaterialDesc& lit = s.materials[s.triangles[0].material];
  CHECK(lit.emission == glm::vec3(2, 3, 4));
  CHECK_FALSE(lit.twoSidedEmission);
  CHECK(s.materials[s.triangles[2].material].emission == glm::vec3(0.0f));  // AttributeEnd ended the light
  // With N the front turns towards the normals (pbrt's FaceForward); a mirroring transform keeps it.
  s = load(dir, std::string(kCamera) + "WorldBegin\n" + light +
                    "Scale 1 1 -1\nShape \"trianglemesh\" \"point3 P\" [ 0 0 0  1 0 0  0 1 0 ] \"integer indices\" [ 0 1 2 ]"
                    " \"normal N\" [ 0 0 1  0 0 1  0 0 1 ]\nIdentity\nScale -1 1 1\n" + kTriangle);
  CHECK(near(front(s.triangles[0]), glm::vec3(0, 0, -1)));  // N (0 0 1) placed by the mirror: -z
  CHECK(near(front(s.triangles[1]), glm::vec3(0, 0, 1)));   // a mirror without N: the same side of the surface
}

TEST_CASE("pbrt: spheres and disks are tessellated within the stated bound; bilinear patches" * doctest::test_suite("cpu pbrt")) {
  TempDir dir;
  Scene s = load(dir, std::string(kCamera) + "WorldBegin\nTranslate 1 2 3\nShape \"sphere\" \"float radius\" [ 2 ]\n");
  double area = 0.0, maxGap = 0.0;
  bool outward = true;
  for (const montecl::SceneTriangle& t : s.triangles) {
    area += 0.5 * glm::length(glm::cross(glm::dvec3(t.v[1] - t.v[0]), glm::dvec3(t.v[2] - t.v[0])));
    const glm::dvec3 c = (glm::dvec3(t.v[0]) + glm::dvec3(t.v[1]) + glm::dvec3(t.v[2])) / 3.0 - glm::dvec3(1, 2, 3);
    maxGap = std::max(maxGap, 2.0 - glm::length(c));
    outward = outward && glm::dot(glm::dvec3(front(t)), c) > 0.0;
  }
  const double exact = 4.0 * M_PI * 4.0;
  CHECK(outward);
  CHECK(area < exact);
  CHECK(area > exact * (1.0 - 1e-3));
  // The facets' centroids lie within the stated bound r (1 - cos(sqrt(2) pi / segments)).
  CHECK(maxGap > 0.0);
  CHECK(maxGap < 2.0 * (1.0 - std::cos(std::sqrt(2.0) * M_PI / montecl::kSphereSegments)));
  MESSAGE("sphere r 2: area deficit " << (1.0 - area / exact) << ", deepest centroid " << maxGap / 2.0 << " r");
  s = load(dir, std::string(kCamera) + "WorldBegin\nShape \"disk\" \"float radius\" [ 1 ] \"float height\" [ 0.5 ]\n");
  area = 0.0;
  for (const montecl::SceneTriangle& t : s.triangles) {
    area += 0.5 * glm::length(glm::cross(t.v[1] - t.v[0], t.v[2] - t.v[0]));
    CHECK(near(front(t), glm::vec3(0, 0, 1), 1e-4f));
    CHECK(t.v[0].z == doctest::Approx(0.5));
  }
  CHECK(area == doctest::Approx(M_PI).epsilon(1e-3));
  // A bilinear patch p00 p10 p01 p11 on the unit square: two triangles, front +z (dpdu x dpdv).
  s = load(dir, std::string(kCamera) + "WorldBegin\nShape \"bilinearmesh\" \"point3 P\" [ 0 0 0  1 0 0  0 1 0  1 1 0 ]"
                                       " \"integer indices\" [ 0 1 2 3 ]\n");
  REQUIRE(s.triangles.size() == 2);
  for (const montecl::SceneTriangle& t : s.triangles) CHECK(near(front(t), glm::vec3(0, 0, 1)));
}

TEST_CASE("pbrt: plymesh goes through montecl's PLY reader, placed and given the current material" * doctest::test_suite("cpu pbrt")) {
  TempDir dir;
  const montecl_test::MeshData tent = montecl_test::tentMesh();
  dir.write("tent.ply", montecl_test::plyText(tent, montecl_test::PlyEncoding::LittleEndian));
  std::vector<montecl::SceneTriangle> alone;
  {
    Scene ply;
    montecl::loadPlyInto(dir.file("tent.ply"), ply);
    alone = ply.triangles;
  }
  Scene s = load(dir, std::string(kCamera) + "WorldBegin\nMaterial \"conductor\"\nTranslate 0 0 -3\n"
                                             "Shape \"plymesh\" \"string filename\" \"tent.ply\"\n");
  REQUIRE(s.triangles.size() == alone.size());
  for (std::size_t i = 0; i < alone.size(); ++i) {
    CHECK(s.materials[s.triangles[i].material].kind == MCL_MATERIAL_conductor);
    CHECK(s.triangles[i].attributes == alone[i].attributes);
    // Its corners (in some rotation, the winding kept or turned to the normals) moved by -3 in z.
    const glm::vec3 sum = s.triangles[i].v[0] + s.triangles[i].v[1] + s.triangles[i].v[2];
    CHECK(near(sum, alone[i].v[0] + alone[i].v[1] + alone[i].v[2] + glm::vec3(0, 0, -9), 1e-5f));
  }
  CHECK(std::find(s.inputFiles.begin(), s.inputFiles.end(), dir.file("tent.ply")) != s.inputFiles.end());
  // A missing PLY file is an error at the parameter naming it.
  const std::string err = loadError(dir, std::string(kCamera) + "WorldBegin\nShape \"plymesh\" \"string filename\" \"gone.ply\"\n");
  CAPTURE(err);
  CHECK(err.find("s.pbrt:5:17: plymesh: cannot open 'gone.ply'") != std::string::npos);
}

TEST_CASE("pbrt: materials map to montecl's kinds with pbrt's parameters" * doctest::test_suite("cpu pbrt")) {
  TempDir dir;
  std::vector<std::string> warnings;
  Scene s = load(dir, std::string(kCamera) + "WorldBegin\n"
                      "MakeNamedMaterial \"red\" \"string type\" [ \"diffuse\" ] \"rgb reflectance\" [ 0.6 0.1 0.1 ]\n"
                      "MakeNamedMaterial \"cu\" \"string type\" [ \"conductor\" ] \"float roughness\" [ 0.25 ]\n"
                      "MakeNamedMaterial \"ag\" \"string type\" [ \"conductor\" ] \"spectrum eta\" \"metal-Ag-eta\""
                      " \"spectrum k\" \"metal-Ag-k\" \"float roughness\" [ 0.04 ] \"bool remaproughness\" false\n"
                      "NamedMaterial \"red\"\n" + kTriangle + "NamedMaterial \"cu\"\n" + kTriangle +
                      "NamedMaterial \"ag\"\n" + kTriangle +
                      "Material \"dielectric\" \"spectrum eta\" \"glass-BK7\"\n" + kTriangle +
                      "Material \"thindielectric\" \"float eta\" 1.33\n" + kTriangle +
                      "Material \"coateddiffuse\" \"rgb reflectance\" [ 0.2 0.3 0.4 ]\n" + kTriangle, &warnings);
  REQUIRE(s.triangles.size() == 6);
  auto mat = [&](int i) { return s.materials[s.triangles[std::size_t(i)].material]; };
  CHECK(mat(0).kind == MCL_MATERIAL_diffuse);
  CHECK(mat(0).albedo == glm::vec3(0.6f, 0.1f, 0.1f));
  CHECK(mat(1).kind == MCL_MATERIAL_conductor);
  CHECK(mat(1).kindAlpha == doctest::Approx(0.5));  // remapped: alpha = sqrt(roughness)
  CHECK(mat(1).eta.x == doctest::Approx(0.201005));  // pbrt's default conductor: copper
  CHECK(mat(2).kindAlpha == doctest::Approx(0.04));  // not remapped
  CHECK(mat(2).k.x == doctest::Approx(4.82835));
  CHECK(mat(3).kind == MCL_MATERIAL_dielectric);
  CHECK(mat(3).ior == doctest::Approx(1.5185).epsilon(1e-3));
  CHECK(mat(4).kind == MCL_MATERIAL_thin_dielectric);
  CHECK(mat(4).ior == doctest::Approx(1.33));
  // coateddiffuse: the coated_diffuse kind with pbrt's defaults (smooth, eta 1.5, thickness 0.01,
  // maxdepth 10, nsamples 1), the base its reflectance, no warning.
  CHECK(mat(5).kind == MCL_MATERIAL_coated_diffuse);
  CHECK(mat(5).albedo == glm::vec3(0.2f, 0.3f, 0.4f));
  CHECK(mat(5).kindAlpha == 0.0f);
  CHECK(mat(5).ior == doctest::Approx(1.5));
  CHECK(mat(5).thickness == doctest::Approx(0.01));
  CHECK(mat(5).layerMaxDepth == 10);
  CHECK(mat(5).layerSamples == 1);
  CHECK(warnings.empty());
  // Every parameter read; a scattering layer is warned; bad values are one line.
  warnings.clear();
  s = load(dir, std::string(kCamera) + "WorldBegin\nMaterial \"coateddiffuse\" \"rgb reflectance\" [ 1 0.5 0 ]"
                " \"float thickness\" 0.1 \"float roughness\" 0.04 \"float eta\" 1.33 \"integer maxdepth\" 20"
                " \"integer nsamples\" 4 \"rgb albedo\" [ 0.5 0.5 0.5 ] \"float g\" 0.3\n" + kTriangle, &warnings);
  CHECK(mat(0).albedo == glm::vec3(1.0f, 0.5f, 0.0f));
  CHECK(mat(0).kindAlpha == doctest::Approx(0.2));  // remapped: sqrt(0.04)
  CHECK(mat(0).ior == doctest::Approx(1.33));
  CHECK(mat(0).thickness == doctest::Approx(0.1));
  CHECK(mat(0).layerMaxDepth == 20);
  CHECK(mat(0).layerSamples == 4);
  CHECK(anyContains(warnings, "s.pbrt:", "scattering layer"));
  // coatedconductor: the coated_conductor kind, conductor.* as the base (the metal's own index,
  // its roughness remapped), interface.* as the coat, the same layer; no warning.
  warnings.clear();
  s = load(dir, std::string(kCamera) + "WorldBegin\nMaterial \"coatedconductor\" \"spectrum conductor.eta\" \"metal-Ag-eta\""
                " \"spectrum conductor.k\" \"metal-Ag-k\" \"float conductor.roughness\" 0.09"
                " \"float interface.roughness\" 0.04 \"float interface.eta\" 1.4 \"float thickness\" 0.2"
                " \"integer maxdepth\" 30 \"integer nsamples\" 2\n" + kTriangle +
                "Material \"coatedconductor\"\n" + kTriangle, &warnings);
  CHECK(mat(0).kind == MCL_MATERIAL_coated_conductor);
  CHECK(mat(0).k.x == doctest::Approx(4.82835));
  CHECK(mat(0).baseAlpha == doctest::Approx(0.3));  // sqrt(0.09)
  CHECK(mat(0).kindAlpha == doctest::Approx(0.2));  // the coat's: sqrt(0.04)
  CHECK(mat(0).ior == doctest::Approx(1.4));
  CHECK(mat(0).thickness == doctest::Approx(0.2));
  CHECK(mat(0).layerMaxDepth == 30);
  CHECK(mat(0).layerSamples == 2);
  // pbrt's defaults: copper, smooth base and coat, eta 1.5, thickness 0.01.
  CHECK(mat(1).kind == MCL_MATERIAL_coated_conductor);
  CHECK(mat(1).eta.x == doctest::Approx(0.201005));
  CHECK(mat(1).baseAlpha == 0.0f);
  CHECK(mat(1).kindAlpha == 0.0f);
  CHECK(mat(1).ior == doctest::Approx(1.5));
  CHECK(mat(1).thickness == doctest::Approx(0.01));
  CHECK(warnings.empty());
}

TEST_CASE("pbrt: image textures become the material's texture; a missing one is an error at its line" * doctest::test_suite("cpu pbrt")) {
  TempDir dir;
  dir.write("wood.png", "the loader only opens it; the renderer decodes it");
  std::vector<std::string> warnings;
  const std::string tex = "Texture \"w\" \"spectrum\" \"imagemap\" \"string filename\" \"wood.png\" \"float uscale\" 2"
                          " \"float vdelta\" 0.5\n"
                          "Texture \"dim\" \"spectrum\" \"scale\" \"texture tex\" \"w\" \"float scale\" 0.25\n"
                          "Texture \"c\" \"spectrum\" \"checkerboard\" \"rgb tex1\" [ 1 0 0 ] \"rgb tex2\" [ 0 0 1 ]\n";
  Scene s = load(dir, std::string(kCamera) + "WorldBegin\n" + tex + "Material \"diffuse\" \"texture reflectance\" \"dim\"\n" +
                          kTriangle + "Material \"diffuse\" \"texture reflectance\" \"c\"\n" + kTriangle, &warnings);
  REQUIRE(s.triangles.size() == 2);
  const montecl::MaterialDesc& wood = s.materials[s.triangles[0].material];
  CHECK(wood.albedoTexture == dir.file("wood.png"));
  CHECK(wood.albedo == glm::vec3(0.25f));                           // the scale texture's factor
  CHECK(wood.albedoSampling.row0 == glm::vec3(2.0f, 0.0f, 0.0f));  // pbrt's s = 2 u
  CHECK(wood.albedoSampling.row1 == glm::vec3(0.0f, 1.0f, 0.5f));  // t = v + 0.5
  // A checkerboard is not rendered: its mean colour, with one warning at its line.
  const montecl::MaterialDesc& checker = s.materials[s.triangles[1].material];
  CHECK(checker.albedoTexture.empty());
  CHECK(checker.albedo == glm::vec3(0.5f, 0.0f, 0.5f));
  CHECK(warnings.size() == 1);
  CHECK(anyContains(warnings, "s.pbrt:7:1:", "checkerboard"));
  // A shape's alpha: an image texture cuts it out; a constant 0 leaves it out.
  s = load(dir, std::string(kCamera) + "WorldBegin\n" + tex + "Shape \"trianglemesh\" \"point3 P\" [ 0 0 0 1 0 0 0 1 0 ]"
                " \"texture alpha\" \"w\"\n" + kTriangle + "Shape \"sphere\" \"float alpha\" 0\n");
  REQUIRE(s.triangles.size() == 2);
  CHECK(s.materials[s.triangles[0].material].alphaTexture == dir.file("wood.png"));
  CHECK(s.materials[s.triangles[1].material].alphaTexture.empty());
  // A texture file that cannot be opened: one error naming the scene file and its line.
  const std::string err = loadError(dir, std::string(kCamera) + "WorldBegin\n"
                                         "Texture \"w\" \"spectrum\" \"imagemap\" \"string filename\" \"nope.png\"\n" + kTriangle);
  CHECK(err.find("s.pbrt: line 5: imagemap") != std::string::npos);
  CHECK(err.find("nope.png") != std::string::npos);
}

TEST_CASE("pbrt: CoordSysTransform \"camera\" places things in the camera's frame" * doctest::test_suite("cpu pbrt")) {
  TempDir dir;
  // The camera of the Cornell box test (at (0, 1, 6.8) looking down -z, no mirror): one unit in
  // front of it along its +z is world (0, 1, 5.8).
  Scene s = load(dir, "Transform [ 1 0 0 0 0 1 0 0 0 0 -1 0 0 -1 6.8 1 ]\n" + std::string(kFilm) +
                          "WorldBegin\nCoordSysTransform \"camera\"\nTranslate 0 0 1\n" + kTriangle);
  REQUIRE(s.triangles.size() == 1);
  CHECK(near(s.triangles[0].v[0], glm::vec3(0, 1, 5.8f), 1e-5f));
}

TEST_CASE("pbrt: lights, instances and Include" * doctest::test_suite("cpu pbrt")) {
  TempDir dir;
  dir.write("part.pbrt", "# included\n" + std::string(kTriangle));
  Scene s = load(dir, std::string(kCamera) + "WorldBegin\n"
                      "LightSource \"point\" \"rgb I\" [ 1 2 3 ] \"point3 from\" [ 0 4 0 ] \"float scale\" 2\n"
                      "LightSource \"distant\" \"point3 from\" [ 0 0 0 ] \"point3 to\" [ 0 -1 0 ] \"rgb L\" [ 1 1 1 ]\n"
                      "LightSource \"infinite\" \"rgb L\" [ 0.5 0.5 0.5 ]\n"
                      "ObjectBegin \"tri\"\nTranslate 0 0 1\n" + kTriangle + "ObjectEnd\n"
                      "Translate 10 0 0\nObjectInstance \"tri\"\nTranslate 10 0 0\nObjectInstance \"tri\"\n"
                      "Include \"part.pbrt\"\n");
  REQUIRE(s.lights.size() == 2);
  CHECK(s.lights[0].kind == montecl::PunctualKind::Point);
  CHECK(near(s.lights[0].position, glm::vec3(0, 4, 0)));
  CHECK(s.lights[0].color == glm::vec3(2, 4, 6));
  CHECK(s.lights[1].kind == montecl::PunctualKind::Directional);
  CHECK(near(s.lights[1].direction, glm::vec3(0, -1, 0)));
  CHECK(s.environment.enabled);
  CHECK(s.environment.radiance == glm::vec3(0.5f));
  REQUIRE(s.meshRanges.size() == 1);
  REQUIRE(s.instances.size() == 2);
  CHECK(s.instances[1].objectToWorld[3][0] == doctest::Approx(20.0));
  CHECK(near(s.triangles[s.meshRanges[0].firstTri].v[0], glm::vec3(0, 0, 1)));  // object space has its own CTM
  CHECK(s.triangles.size() == 2);  // the included triangle and the object's one
  // pbrt normalises a light's non-RGB spectrum to luminance 1 before its scale: a flat spectrum
  // of 7 is white 1 (x scale 3); RGB is taken as it is.
  s = load(dir, std::string(kCamera) + "WorldBegin\nAreaLightSource \"diffuse\" \"spectrum L\" [ 400 7 700 7 ] \"float scale\" 3\n" +
                    kTriangle);
  CHECK(near(s.materials[s.triangles[0].material].emission, glm::vec3(3.0f), 1e-4f));
}

TEST_CASE("pbrt: malformed input is one error naming file:line:column" * doctest::test_suite("cpu pbrt")) {
  TempDir dir;
  const std::string pre = std::string(kCamera) + "WorldBegin\n";  // lines 1-4
  struct Case {
    std::string text, where, what;
  };
  const std::vector<Case> cases = {
      {pre + "Shape \"trianglemesh\" \"point3 P\" [ 0 0 0 1 0 ]\n", "s.pbrt:5:22:", "not a multiple of 3"},
      {pre + "Shape \"trianglemesh\" \"point3 P\" [ 0 0 0 1 0 0 0 1 0 ] \"integer indices\" [ 0 1 5 ]\n", "s.pbrt:5:", "out of range"},
      {pre + "Frobnicate 1 2\n", "s.pbrt:5:1:", "unknown directive 'Frobnicate'"},
      {pre + "Shape \"sphere\" \"float radius\" [ 1 \n", "s.pbrt:5:16:", "']' is missing"},
      {pre + "Shape \"sphere\" \"float radius [ 1 ]\n", "s.pbrt:5:16:", "unterminated string"},
      {pre + "Translate 1 2\nShape \"sphere\"\n", "s.pbrt:6:1:", "Translate takes 3"},
      {pre + "NamedMaterial \"nope\"\n", "s.pbrt:5:15:", "not defined"},
      {pre + "AttributeEnd\n", "s.pbrt:5:1:", "without a matching AttributeBegin"},
      {pre + "Include \"missing.pbrt\"\n", "s.pbrt:5:9:", "cannot open"},
      {pre + "Shape \"sphere\" \"float radius\" [ 1x ]\n", "s.pbrt:5:33:", "malformed number"},
      {pre + "Shape \"sphere\" \"floot radius\" [ 1 ]\n", "s.pbrt:5:16:", "unknown parameter type 'floot'"},
      {"WorldBegin\nCamera \"perspective\"\n", "s.pbrt:2:1:", "not allowed after WorldBegin"},
  };
  for (const Case& c : cases) {
    const std::string err = loadError(dir, c.text);
    CAPTURE(c.text);
    CAPTURE(err);
    CHECK(err.find(c.where) != std::string::npos);
    CHECK(err.find(c.what) != std::string::npos);
    CHECK(err.find('\n') == std::string::npos);
  }
}

TEST_CASE("pbrt: unsupported but valid input warns with file:line and the scene loads" * doctest::test_suite("cpu pbrt")) {
  TempDir dir;
  std::vector<std::string> warnings;
  Scene s = load(dir, std::string(kCamera) + "PixelFilter \"frobnicate\"\nWorldBegin\n"
                      "MakeNamedMedium \"fog\" \"string type\" [ \"homogeneous\" ]\n"
                      "Shape \"curve\" \"point3 P\" [ 0 0 0 1 0 0 2 0 0 3 0 0 ]\n"
                      "Shape \"sphere\" \"float radius\" 1 \"float zmin\" -0.5 \"float frobnicity\" 3\n", &warnings);
  CHECK(!s.triangles.empty());
  CHECK(anyContains(warnings, "s.pbrt:4:1:", "PixelFilter"));
  CHECK(anyContains(warnings, "s.pbrt:6:1:", "MakeNamedMedium"));
  CHECK(anyContains(warnings, "s.pbrt:7:1:", "curve"));
  CHECK(anyContains(warnings, "s.pbrt:8:1:", "zmin"));
  CHECK(anyContains(warnings, "s.pbrt:8:", "'float frobnicity' not used"));
  CHECK(warnings.size() == 5);
}

TEST_CASE("pbrt: the equal-area octahedral mapping is pbrt-v4's and keeps areas" * doctest::test_suite("cpu pbrt")) {
  using montecl::equalAreaSphereToSquare;
  auto at = [](double x, double y, double z) { return equalAreaSphereToSquare(glm::normalize(glm::dvec3(x, y, z))); };
  CHECK(glm::length(at(0, 0, 1) - glm::dvec2(0.5, 0.5)) < 1e-12);  // +z at the centre
  CHECK(glm::length(at(1, 0, 0) - glm::dvec2(1.0, 0.5)) < 1e-12);
  CHECK(glm::length(at(-1, 0, 0) - glm::dvec2(0.0, 0.5)) < 1e-12);
  CHECK(glm::length(at(0, 1, 0) - glm::dvec2(0.5, 1.0)) < 1e-12);
  CHECK(glm::length(at(0, -1, 0) - glm::dvec2(0.5, 0.0)) < 1e-12);
  CHECK(glm::length(at(1e-9, 1e-9, -1) - glm::dvec2(1.0, 1.0)) < 1e-6);  // -z at the corners
  // Equal area: uniform directions fall uniformly into an 8 x 8 grid of the square (every cell
  // within 5 standard deviations of n / 64).
  const int n = 256000;
  std::vector<int> cells(64, 0);
  std::uint64_t state = 12345;
  auto uniform = [&state] {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return double(state >> 11) / 9007199254740992.0;
  };
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - 2.0 * uniform(), phi = 2.0 * M_PI * uniform(), s = std::sqrt(std::max(0.0, 1.0 - z * z));
    const glm::dvec2 uv = equalAreaSphereToSquare(glm::dvec3(s * std::cos(phi), s * std::sin(phi), z));
    cells[std::size_t(std::min(7, int(uv.y * 8)) * 8 + std::min(7, int(uv.x * 8)))]++;
  }
  const double expect = n / 64.0, sigma = std::sqrt(expect * (1.0 - 1.0 / 64.0));
  for (int c : cells) CHECK(std::abs(c - expect) < 5.0 * sigma);
}

TEST_CASE("pbrt: an infinite light's map is resampled through its transform" * doctest::test_suite("cpu pbrt")) {
  TempDir dir;
  dir.write("sky.exr", "only opened by the loader");
  // pbrt-v4 scenes turn their maps' +z up with Rotate -90 1 0 0: the map's centre (+z) lights from +y.
  Scene s = load(dir, std::string(kCamera) + "WorldBegin\nAttributeBegin\nRotate -90 1 0 0\n"
                                             "LightSource \"infinite\" \"string filename\" \"sky.exr\"\nAttributeEnd\n" + kTriangle);
  REQUIRE(s.environment.enabled);
  CHECK(s.environment.equalArea);
  CHECK(s.environment.file == dir.file("sky.exr"));
  // A 16 x 16 map, red in its 4 centre texels: the red texels of the latitude-longitude map are
  // around +y (montecl's row 0).
  const int side = 16;
  std::vector<glm::vec3> square(std::size_t(side * side), glm::vec3(0.0f, 0.0f, 1.0f));
  for (int y = 7; y <= 8; ++y)
    for (int x = 7; x <= 8; ++x) square[std::size_t(y * side + x)] = glm::vec3(1.0f, 0.0f, 0.0f);
  int width = 0, height = 0;
  const std::vector<glm::vec3> ll = montecl::latLongFromEqualArea(square, side, s.environment.mapFromWorld, width, height);
  CHECK(width == 32);
  CHECK(height == 16);
  glm::dvec3 sum(0.0);
  int red = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      if (ll[std::size_t(y * width + x)].x == 1.0f) {
        const double theta = M_PI * (y + 0.5) / height, phi = 2.0 * M_PI * (x + 0.5) / width;
        sum += glm::dvec3(std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi));
        ++red;
      }
  REQUIRE(red > 0);
  CHECK(glm::normalize(sum).y > 0.99);
}

TEST_CASE("pbrt: a file of 100k inline triangles loads in under a second" * doctest::test_suite("cpu slow uninstrumented")) {
#if defined(__SANITIZE_ADDRESS__) || !defined(NDEBUG)
  MCL_SKIP_UNLESS(false, "load times are measured in release builds without sanitizers");
#endif
  TempDir dir;
  const int n = 100000;
  std::string text = std::string(kCamera) + "WorldBegin\nShape \"trianglemesh\" \"point3 P\" [\n";
  std::uint64_t state = 7;
  for (int i = 0; i < 3 * n; ++i) {
    for (int c = 0; c < 3; ++c) {
      state = state * 6364136223846793005ull + 1442695040888963407ull;
      text += std::to_string(double(state >> 11) / 9007199254740992.0) + (c < 2 ? " " : "\n");
    }
  }
  text += "] \"integer indices\" [\n";
  for (int i = 0; i < 3 * n; ++i) text += std::to_string(i) + (i % 12 == 11 ? "\n" : " ");
  text += "]\n";
  dir.write("s.pbrt", text);
  std::vector<std::string> warnings;
  const auto t0 = std::chrono::steady_clock::now();
  const Scene s = montecl::loadScene(dir.file("s.pbrt"), warnings);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double megabytes = double(text.size()) / 1e6;
  MESSAGE(megabytes << " MB, " << s.triangles.size() << " triangles loaded in " << seconds << " s");
  CHECK(s.triangles.size() > std::size_t(n) * 99 / 100);  // random triangles: a few may be degenerate
  CHECK(seconds < 1.0);
}

TEST_CASE("pbrt: PixelFilter becomes render.filter with pbrt's defaults and parameters" * doctest::test_suite("cpu pbrt")) {
  TempDir dir;
  std::vector<std::string> warnings;
  const auto withFilter = [&](const std::string& filter) {
    return load(dir, filter + "\n" + std::string(kCamera) + "WorldBegin\n" + kTriangle, &warnings).render.filter;
  };
  // No PixelFilter: montecl's box (pbrt's own default is a gaussian; the default keeps montecl's images).
  CHECK(load(dir, std::string(kCamera) + "WorldBegin\n" + kTriangle).render.filter == montecl::PixelFilter{});
  montecl::PixelFilter f = withFilter("PixelFilter \"gaussian\"");
  CHECK(montecl::filterText(f) == "gaussian");  // radius 1.5, sigma 0.5: pbrt-v4's
  CHECK(warnings.empty());
  f = withFilter("PixelFilter \"mitchell\" \"float xradius\" 1.5 \"float yradius\" 1.5 \"float B\" 0.5 \"float C\" 0.25");
  CHECK(f.type == montecl::FilterType::Mitchell);
  CHECK(f.radius == 1.5f);
  CHECK(f.b == 0.5f);
  CHECK(f.c == 0.25f);
  f = withFilter("PixelFilter \"sinc\" \"float tau\" 2");
  CHECK(montecl::filterText(f) == "lanczos,tau=2");
  f = withFilter("PixelFilter \"triangle\" \"float xradius\" 1 \"float yradius\" 2");
  CHECK(montecl::filterText(f) == "triangle");  // the larger radius, 2: the triangle's default
  CHECK(anyContains(warnings, "s.pbrt:1:1", "one radius"));
  f = withFilter("PixelFilter \"box\" \"float xradius\" 0.5 \"float yradius\" 0.5");
  CHECK(f == montecl::PixelFilter{});
  CHECK(warnings.empty());
}

}  // namespace test_file_pbrt_parser
