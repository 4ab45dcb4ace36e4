// test_mitsuba_parser.cpp: the Mitsuba 3 XML reader (host/scene/mitsuba_*.cpp) on small inline
// scene files, through every tag family: $name defaults and <include>, transforms in order, the
// sensor (fov_axis, film, sampler, a mirroring to_world), integrators and their depth, shapes,
// BSDFs as montecl kinds, emitters, textures, Mitsuba 0.6's camelCase; unsupported input is one
// file:line:column warning and bad input one file:line:column error.
#include <doctest/doctest.h>

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "mesh_files.h"
#include "scene/tessellate.h"
#include "scene/scene.h"
#include "util/errors.h"

namespace test_file_mitsuba_parser {  // keeps this file's helpers apart in a unity batch

using montecl::Scene;
using montecl_test::TempDir;

namespace {

const char* kHead = "<scene version=\"3.0.0\">\n";
// A unit rectangle in front of the default camera, so that a scene has something to render.
const char* kRect = "<shape type=\"rectangle\"/>\n";

Scene load(const TempDir& dir, const std::string& body, std::vector<std::string>* warningsOut = nullptr) {
  dir.write("s.xml", kHead + body + "</scene>\n");
  std::vector<std::string> warnings;
  Scene s = montecl::loadScene(dir.file("s.xml"), warnings, montecl::MissingTextures::Warn);
  if (warningsOut) *warningsOut = warnings;
  return s;
}

std::string loadError(const TempDir& dir, const std::string& text) {
  dir.write("e.xml", text);
  std::vector<std::string> warnings;
  try {
    montecl::loadScene(dir.file("e.xml"), warnings);
  } catch (const montecl::InputError& e) {
    return e.what();
  }
  return "";
}

bool near(glm::vec3 a, glm::vec3 b, float eps = 1e-5f) { return glm::length(a - b) <= eps; }

bool anyWarning(const std::vector<std::string>& w, const std::string& part) {
  return std::any_of(w.begin(), w.end(), [&](const std::string& s) { return s.find(part) != std::string::npos; });
}

}  // namespace

TEST_CASE("mitsuba: $name defaults, include, the sensor's fov axis, film and sampler" * doctest::test_suite("cpu mitsuba")) {
  TempDir dir;
  dir.write("part.xml", "<scene version=\"3.0.0\"><shape type=\"disk\"/></scene>\n");
  const Scene s = load(dir, "<default name=\"w\" value=\"40\"/><default name=\"spp\" value=\"12\"/>\n"
                            "<sensor type=\"perspective\"><float name=\"fov\" value=\"60\"/>\n"
                            "<film type=\"hdrfilm\"><integer name=\"width\" value=\"$w\"/><integer name=\"height\" value=\"20\"/></film>\n"
                            "<sampler type=\"stratified\"><integer name=\"sample_count\" value=\"$spp\"/><integer name=\"seed\" value=\"9\"/></sampler>"
                            "</sensor>\n<include filename=\"part.xml\"/>\n");
  CHECK(s.camera.width == 40);
  CHECK(s.camera.height == 20);
  CHECK(s.render.spp == 12);
  CHECK(s.render.seed == 9u);
  CHECK(s.render.sampler == montecl::Sampler::Sobol);  // a stratified kind: montecl's Sobol points
  // fov 60 along x (Mitsuba's default axis) on a 40 x 20 image: tan(fov_y / 2) = tan(30 deg) / 2.
  CHECK(s.camera.fovY == doctest::Approx(2.0 * glm::degrees(std::atan(std::tan(glm::radians(30.0)) * 0.5))).epsilon(1e-5));
  CHECK(s.triangles.size() == std::size_t(montecl::kSphereSegments));  // the included disk
  CHECK(std::find(s.inputFiles.begin(), s.inputFiles.end(), dir.file("part.xml")) != s.inputFiles.end());
  // Mitsuba's defaults without a sensor or integrator: path, unlimited depth, 4 independent samples, 768 x 576.
  const Scene d = load(dir, kRect);
  CHECK(d.render.integrator == montecl::Integrator::Path);
  CHECK(d.render.maxDepth == -1);
  CHECK(d.render.spp == 4);
  CHECK(d.render.sampler == montecl::Sampler::Independent);
  CHECK(d.camera.width == 768);
  CHECK(d.camera.height == 576);
}

TEST_CASE("mitsuba: transforms apply in order; a lookat camera is kept as written" * doctest::test_suite("cpu mitsuba")) {
  TempDir dir;
  // scale 2, then a quarter turn about +x (+y -> +z), then translate: (1, 1, 0) -> (2, 0, 2) + (0, 0, 5).
  const Scene s = load(dir, "<sensor type=\"perspective\"><transform name=\"to_world\"><lookat origin=\"1, 2, 3\" target=\"1 2 0\" up=\"0 1 0\"/>"
                            "</transform></sensor>\n<shape type=\"rectangle\"><transform name=\"to_world\"><scale value=\"2\"/>"
                            "<rotate x=\"1\" angle=\"90\"/><translate value=\"0 0 5\"/></transform></shape>\n"
                            "<shape type=\"rectangle\"><transform name=\"to_world\"><matrix value=\"1 0 0 10  0 1 0 0  0 0 1 0  0 0 0 1\"/>"
                            "</transform></shape>\n");
  REQUIRE(s.triangles.size() == 4);
  CHECK(near(s.triangles[0].v[2], glm::vec3(2, 0, 7)));  // the rectangle's corner (1, 1, 0)
  CHECK(near(s.triangles[2].v[0], glm::vec3(9, -1, 0)));  // (-1, -1, 0) moved by the matrix's +10 x
  CHECK(s.camera.position == glm::vec3(1, 2, 3));
  CHECK(s.camera.target == glm::vec3(1, 2, 0));
}

TEST_CASE("mitsuba: a sensor whose to_world mirrors shows Mitsuba's picture (the world is reflected)" * doctest::test_suite("cpu mitsuba")) {
  TempDir dir;
  // The camera at +5 z looks at the origin; Mitsuba's image right is its -x. scale x -1 first
  // mirrors it: Mitsuba's picture then shows world +x on the right... of montecl's picture the left.
  const std::string shape = "<shape type=\"sphere\"><point name=\"center\" value=\"2 0 0\"/><float name=\"radius\" value=\"0.1\"/></shape>\n";
  const Scene plain = load(dir, "<sensor type=\"perspective\"><transform name=\"to_world\"><lookat origin=\"0 0 5\" target=\"0 0 0\" up=\"0 1 0\"/>"
                                "</transform></sensor>\n" + shape);
  const Scene mirrored = load(dir, "<sensor type=\"perspective\"><transform name=\"to_world\"><scale x=\"-1\"/>"
                                   "<lookat origin=\"0 0 5\" target=\"0 0 0\" up=\"0 1 0\"/></transform></sensor>\n" + shape);
  CHECK(plain.boundsMin.x > 1.8f);
  CHECK(mirrored.boundsMax.x < -1.8f);  // the sphere crosses to the other side of the picture
  CHECK(mirrored.camera.position == glm::vec3(0, 0, 5));
}

TEST_CASE("mitsuba: integrators path and direct; max_depth in Mitsuba's convention is montecl's" * doctest::test_suite("cpu mitsuba")) {
  TempDir dir;
  Scene s = load(dir, std::string("<integrator type=\"path\"><integer name=\"max_depth\" value=\"2\"/><integer name=\"rr_depth\" value=\"3\"/></integrator>") + kRect);
  CHECK(s.render.integrator == montecl::Integrator::Path);
  CHECK(s.render.maxDepth == 2);  // 2: direct light, in both
  CHECK(s.render.rrDepth == 3);
  s = load(dir, std::string("<integrator type=\"direct\"><integer name=\"emitter_samples\" value=\"4\"/><integer name=\"bsdf_samples\" value=\"0\"/></integrator>") + kRect);
  CHECK(s.render.integrator == montecl::Integrator::Direct);
  CHECK(s.render.lightSamples == 4);
  CHECK(s.render.directSampling == montecl::DirectSampling::Light);
  std::vector<std::string> w;
  s = load(dir, std::string("<integrator type=\"volpath\"/>") + kRect, &w);
  CHECK(s.render.integrator == montecl::Integrator::Path);
  CHECK(anyWarning(w, "s.xml:2:1: integrator \"volpath\": montecl renders it with its path tracer"));
}

TEST_CASE("mitsuba: shapes obj, ply, rectangle, cube, sphere, disk, and their fronts" * doctest::test_suite("cpu mitsuba")) {
  TempDir dir;
  const montecl_test::MeshData tent = montecl_test::tentMesh();
  dir.write("tent.obj", montecl_test::objText(tent));
  dir.write("tent.ply", montecl_test::plyText(tent, montecl_test::PlyEncoding::Ascii));
  const Scene obj = load(dir, "<shape type=\"obj\"><string name=\"filename\" value=\"tent.obj\"/></shape>\n");
  const Scene ply = load(dir, "<shape type=\"ply\"><string name=\"filename\" value=\"tent.ply\"/></shape>\n");
  REQUIRE(obj.triangles.size() == ply.triangles.size());
  REQUIRE((obj.triangles[0].attributes & montecl::kHasUv) != 0);
  // Mitsuba reads a PLY's v as it stands and flips an OBJ's: montecl's v of the PLY is 1 - v.
  CHECK(obj.triangles[0].uv[1].y == doctest::Approx(1.0f - ply.triangles[0].uv[1].y));
  CHECK(load(dir, "<shape type=\"cube\"/>").triangles.size() == 12);
  const Scene cube = load(dir, "<shape type=\"cube\"/>");
  for (const montecl::SceneTriangle& t : cube.triangles) {  // every face's front points out
    const glm::vec3 n = glm::cross(t.v[1] - t.v[0], t.v[2] - t.v[0]);
    CHECK(glm::dot(n, (t.v[0] + t.v[1] + t.v[2]) / 3.0f) > 0.0f);
  }
  const Scene rect = load(dir, kRect), flipped = load(dir, "<shape type=\"rectangle\"><boolean name=\"flip_normals\" value=\"true\"/></shape>");
  const glm::vec3 front = glm::cross(rect.triangles[0].v[1] - rect.triangles[0].v[0], rect.triangles[0].v[2] - rect.triangles[0].v[0]);
  const glm::vec3 back = glm::cross(flipped.triangles[0].v[1] - flipped.triangles[0].v[0], flipped.triangles[0].v[2] - flipped.triangles[0].v[0]);
  CHECK(front.z > 0.0f);  // Mitsuba's rectangle faces +z
  CHECK(back.z < 0.0f);
  const Scene sphere = load(dir, "<shape type=\"sphere\"><point name=\"center\" x=\"0\" y=\"0\" z=\"3\"/><float name=\"radius\" value=\"0.5\"/></shape>");
  CHECK(sphere.boundsMin.z == doctest::Approx(2.5f).epsilon(1e-4));
  CHECK(sphere.boundsMax.x == doctest::Approx(0.5f).epsilon(1e-3));
  CHECK(load(dir, "<shape type=\"disk\"/>").triangles.size() == std::size_t(montecl::kSphereSegments));
}

TEST_CASE("mitsuba: BSDFs map to montecl's kinds" * doctest::test_suite("cpu mitsuba")) {
  TempDir dir;
  auto material = [&](const std::string& bsdf, std::vector<std::string>* w = nullptr) {
    const Scene s = load(dir, "<shape type=\"rectangle\">" + bsdf + "</shape>\n", w);
    REQUIRE(s.materials.size() == 1);
    return s.materials[0];
  };
  montecl::MaterialDesc m = material("<bsdf type=\"twosided\"><bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"0.2 0.3 0.4\"/></bsdf></bsdf>");
  CHECK(m.kind == MCL_MATERIAL_diffuse);
  CHECK(m.albedo == glm::vec3(0.2f, 0.3f, 0.4f));
  m = material("<bsdf type=\"dielectric\"><float name=\"int_ior\" value=\"1.5\"/><float name=\"ext_ior\" value=\"1.25\"/></bsdf>");
  CHECK(m.kind == MCL_MATERIAL_dielectric);
  CHECK(m.ior == doctest::Approx(1.2f));
  m = material("<bsdf type=\"roughdielectric\"><string name=\"distribution\" value=\"ggx\"/><float name=\"alpha\" value=\"0.3\"/>"
               "<string name=\"int_ior\" value=\"water\"/><string name=\"ext_ior\" value=\"vacuum\"/></bsdf>");
  CHECK(m.kind == MCL_MATERIAL_dielectric);
  CHECK(m.kindAlpha == doctest::Approx(0.3f));
  CHECK(m.ior == doctest::Approx(1.333f));
  CHECK(material("<bsdf type=\"thindielectric\"/>").kind == MCL_MATERIAL_thin_dielectric);
  m = material("<bsdf type=\"conductor\"/>");  // material "none": a perfect mirror
  CHECK(m.kind == MCL_MATERIAL_conductor);
  CHECK(m.eta == glm::vec3(0.0f));
  CHECK(m.k == glm::vec3(1.0f));
  std::vector<std::string> w;
  m = material("<bsdf type=\"roughconductor\"><string name=\"material\" value=\"Au\"/><float name=\"alpha\" value=\"0.2\"/></bsdf>", &w);
  CHECK(m.kind == MCL_MATERIAL_conductor);
  CHECK(m.kindAlpha == doctest::Approx(0.2f));
  CHECK(m.eta.x == doctest::Approx(0.143036f));
  CHECK(m.beckmann);  // Mitsuba's default distribution, rendered as such
  CHECK(m.conductorFactor == glm::vec3(1.0f));
  CHECK(!anyWarning(w, "read as GGX"));
  m = material("<bsdf type=\"roughconductor\"><string name=\"distribution\" value=\"ggx\"/>"
               "<rgb name=\"specular_reflectance\" value=\"0.3 0.4 0.5\"/></bsdf>", &w);
  CHECK(!m.beckmann);
  CHECK(m.conductorFactor == glm::vec3(0.3f, 0.4f, 0.5f));
  CHECK(!anyWarning(w, "specular_reflectance"));
  CHECK_THROWS_AS(material("<bsdf type=\"conductor\"><float name=\"specular_reflectance\" value=\"-1\"/></bsdf>"),
                  montecl::InputError);
  material("<bsdf type=\"roughdielectric\"/>", &w);  // a dielectric's Beckmann is still read as GGX
  CHECK(anyWarning(w, "the beckmann distribution is read as GGX"));
  m = material("<bsdf type=\"roughplastic\"><rgb name=\"diffuse_reflectance\" value=\"0.1 0.2 0.3\"/><float name=\"alpha\" value=\"0.25\"/></bsdf>", &w);
  CHECK(m.kind == MCL_MATERIAL_metal_rough);
  CHECK(m.metallic == 0.0f);
  CHECK(m.roughness == doctest::Approx(0.5f));  // metal_rough squares it: alpha 0.25
  CHECK(m.albedo == glm::vec3(0.1f, 0.2f, 0.3f));
  CHECK(std::count_if(w.begin(), w.end(), [](const std::string& s) { return s.find("approximated by montecl's metal_rough") != std::string::npos; }) == 1);
  dir.write("leaf.png", "any bytes: the reader does not decode");
  m = material("<bsdf type=\"mask\"><texture name=\"opacity\" type=\"bitmap\"><string name=\"filename\" value=\"leaf.png\"/></texture>"
               "<bsdf type=\"bumpmap\"><texture type=\"bitmap\"><string name=\"filename\" value=\"leaf.png\"/></texture>"
               "<float name=\"scale\" value=\"0.5\"/><bsdf type=\"diffuse\"/></bsdf></bsdf>");
  CHECK(m.alphaTexture == dir.file("leaf.png"));
  CHECK(m.alphaCutoff == 0.5f);
  CHECK(m.bumpTexture == dir.file("leaf.png"));
  CHECK(m.bumpScale == 0.5f);
  // A mask of constant opacity 0 leaves the shape out.
  CHECK_THROWS_AS(load(dir, "<shape type=\"rectangle\"><bsdf type=\"mask\"><float name=\"opacity\" value=\"0\"/><bsdf type=\"diffuse\"/></bsdf></shape>"),
                  montecl::InputError);  // ... and a scene of nothing else has nothing to render
}

TEST_CASE("mitsuba: emitters area, constant, envmap, point, spot, directional" * doctest::test_suite("cpu mitsuba")) {
  TempDir dir;
  dir.write("sky.exr", "not decoded by the reader");
  const Scene s = load(dir, "<shape type=\"rectangle\"><emitter type=\"area\"><rgb name=\"radiance\" value=\"1 2 3\"/></emitter></shape>\n"
                            "<emitter type=\"envmap\"><string name=\"filename\" value=\"sky.exr\"/><float name=\"scale\" value=\"2\"/>"
                            "<transform name=\"to_world\"><rotate y=\"1\" angle=\"30\"/></transform></emitter>\n"
                            "<emitter type=\"point\"><point name=\"position\" value=\"1 2 3\"/><rgb name=\"intensity\" value=\"5\"/></emitter>\n"
                            "<emitter type=\"spot\"><transform name=\"to_world\"><lookat origin=\"0 4 0\" target=\"0 0 0\" up=\"0 0 1\"/></transform>"
                            "<rgb name=\"intensity\" value=\"7\"/><float name=\"cutoff_angle\" value=\"40\"/></emitter>\n"
                            "<emitter type=\"directional\"><vector name=\"direction\" value=\"0 -2 0\"/><rgb name=\"irradiance\" value=\"3\"/></emitter>\n");
  REQUIRE(s.materials.size() == 1);
  CHECK(s.materials[0].emission == glm::vec3(1, 2, 3));
  CHECK_FALSE(s.materials[0].twoSidedEmission);  // Mitsuba's area emitters are one-sided
  CHECK(s.environment.enabled);
  CHECK(s.environment.file == dir.file("sky.exr"));
  CHECK(s.environment.scale == 2.0f);
  CHECK(s.environment.rotateYDegrees == doctest::Approx(30.0f));
  REQUIRE(s.lights.size() == 3);
  CHECK(s.lights[0].kind == montecl::PunctualKind::Point);
  CHECK(s.lights[0].position == glm::vec3(1, 2, 3));
  CHECK(s.lights[0].color == glm::vec3(5.0f));
  CHECK(s.lights[1].kind == montecl::PunctualKind::Spot);
  CHECK(near(s.lights[1].direction, glm::vec3(0, -1, 0)));
  CHECK(s.lights[1].cutoffDegrees == 40.0f);
  CHECK(s.lights[1].beamDegrees == 30.0f);  // Mitsuba's default: 3/4 of the cutoff
  CHECK(s.lights[2].kind == montecl::PunctualKind::Directional);
  CHECK(near(s.lights[2].direction, glm::vec3(0, -1, 0)));
  const Scene c = load(dir, std::string("<emitter type=\"constant\"><rgb name=\"radiance\" value=\"0.5\"/></emitter>") + kRect);
  CHECK(c.environment.enabled);
  CHECK(c.environment.file.empty());
  CHECK(c.environment.radiance == glm::vec3(0.5f));
}

TEST_CASE("mitsuba: textures bitmap (wrap, to_uv) and checkerboard (its mean, warned)" * doctest::test_suite("cpu mitsuba")) {
  TempDir dir;
  dir.write("wood.png", "not decoded by the reader");
  std::vector<std::string> w;
  const Scene s = load(dir, "<texture type=\"bitmap\" id=\"wood\"><string name=\"filename\" value=\"wood.png\"/>"
                            "<string name=\"wrap_mode\" value=\"clamp\"/><transform name=\"to_uv\"><scale x=\"2\" y=\"3\"/></transform></texture>\n"
                            "<shape type=\"rectangle\"><bsdf type=\"diffuse\"><ref name=\"reflectance\" id=\"wood\"/></bsdf></shape>\n"
                            "<shape type=\"disk\"><bsdf type=\"diffuse\"><texture name=\"reflectance\" type=\"checkerboard\">"
                            "<rgb name=\"color0\" value=\"1 0 0\"/><rgb name=\"color1\" value=\"0 0 1\"/></texture></bsdf></shape>\n", &w);
  REQUIRE(s.materials.size() == 2);
  const montecl::MaterialDesc& wood = s.materials[0];
  CHECK(wood.albedoTexture == dir.file("wood.png"));
  CHECK(wood.albedo == glm::vec3(1.0f));
  CHECK(wood.albedoSampling.wrapS == 1u);  // MCL_WRAP_CLAMP
  // Mitsuba's (2u, 3v) in montecl's v-up convention: u' = 2u, v' = 3v + (1 - 3).
  CHECK(wood.albedoSampling.row0 == glm::vec3(2, 0, 0));
  CHECK(wood.albedoSampling.row1 == glm::vec3(0, 3, -2));
  CHECK(s.materials[1].albedo == glm::vec3(0.5f, 0.0f, 0.5f));
  CHECK(anyWarning(w, "s.xml:4:41: texture \"checkerboard\": montecl has no procedural textures"));
}

TEST_CASE("mitsuba: Mitsuba 0.6 files (camelCase names) read as Mitsuba 3's" * doctest::test_suite("cpu mitsuba")) {
  TempDir dir;
  dir.write("old.xml", "<scene version=\"0.6.0\"><integrator type=\"path\"><integer name=\"maxDepth\" value=\"4\"/></integrator>"
                       "<sensor type=\"perspective\"><float name=\"fov\" value=\"45\"/><string name=\"fovAxis\" value=\"y\"/>"
                       "<transform name=\"toWorld\"><lookAt origin=\"0 0 5\" target=\"0 0 0\" up=\"0 1 0\"/></transform>"
                       "<sampler type=\"independent\"><integer name=\"sampleCount\" value=\"7\"/></sampler></sensor>"
                       "<shape type=\"rectangle\"><bsdf type=\"dielectric\"><float name=\"intIOR\" value=\"1.6\"/></bsdf></shape></scene>\n");
  std::vector<std::string> w;
  const Scene s = montecl::loadScene(dir.file("old.xml"), w);
  CHECK(s.render.maxDepth == 4);
  CHECK(s.render.spp == 7);
  CHECK(s.camera.fovY == 45.0f);
  CHECK(s.camera.position == glm::vec3(0, 0, 5));
  CHECK(s.materials[0].ior == doctest::Approx(1.6f / 1.00028f));
  CHECK(w.empty());
}

TEST_CASE("mitsuba: what montecl leaves out is one warning naming file:line:column" * doctest::test_suite("cpu mitsuba")) {
  TempDir dir;
  std::vector<std::string> w;
  load(dir, "<shape type=\"cylinder\"/>\n<medium type=\"homogeneous\"/>\n"
            "<shape type=\"rectangle\"><bsdf type=\"diffuse\"><float name=\"nonsense\" value=\"1\"/></bsdf></shape>\n"
            "<emitter type=\"projector\"/>\n",
       &w);
  CHECK(anyWarning(w, "s.xml:2:1: shape \"cylinder\" not read by montecl"));
  CHECK(anyWarning(w, "s.xml:3:1: <medium>: montecl renders no participating media"));
  CHECK(anyWarning(w, "s.xml:4:46: bsdf \"diffuse\": property 'nonsense' not read by montecl, ignored"));
  CHECK(anyWarning(w, "s.xml:5:1: emitter \"projector\" not read by montecl"));
  CHECK(anyWarning(w, "s.xml:4:1: shape: its BSDF is one-sided in Mitsuba"));
}

TEST_CASE("mitsuba: bad input is one InputError naming file:line:column" * doctest::test_suite("cpu mitsuba")) {
  TempDir dir;
  const std::string head = kHead;
  CHECK(loadError(dir, head + "<shape type=\"rectangle\">\n</scene>\n").find("/e.xml:3:3: malformed XML") != std::string::npos);
  CHECK(loadError(dir, head + "  <integrator type=\"path\"><integer name=\"max_depth\" value=\"$depth\"/></integrator>\n</scene>\n")
            .find("/e.xml:2:27: '$depth' is not defined") != std::string::npos);
  CHECK(loadError(dir, head + "<integrator type=\"path\"><integer name=\"max_depth\" value=\"2.5\"/></integrator>\n" + kRect + "</scene>\n")
            .find("/e.xml:2:25: 'max_depth' must be one integer") != std::string::npos);
  CHECK(loadError(dir, head + "<integrator type=\"path\"><integer name=\"max_depth\" value=\"0\"/></integrator>\n" + kRect + "</scene>\n")
            .find("/e.xml:2:25: path: max_depth must be -1 (unlimited) or >= 1") != std::string::npos);
  CHECK(loadError(dir, head + "<shape type=\"rectangle\"><transform name=\"to_world\"><shear/></transform></shape>\n</scene>\n")
            .find("/e.xml:2:52: <transform>: unknown step <shear>") != std::string::npos);
  CHECK(loadError(dir, head + "<shape type=\"rectangle\"><ref id=\"nobody\"/></shape>\n</scene>\n").find("/e.xml:2:25: <ref id=\"nobody\">: no element has that id") != std::string::npos);
  CHECK(loadError(dir, head + "<include filename=\"absent.xml\"/>\n</scene>\n").find("/e.xml:2:1: cannot open") != std::string::npos);
  CHECK(loadError(dir, head + "<shape type=\"obj\"><string name=\"filename\" value=\"absent.obj\"/></shape>\n</scene>\n")
            .find("/e.xml:2:19: obj: cannot open 'absent.obj'") != std::string::npos);
  CHECK(loadError(dir, "<scena/>\n").find("/e.xml:1:1: the root element is <scena>") != std::string::npos);
  CHECK(loadError(dir, head + "<shape type=\"rectangle\" id=\"a\"/><shape type=\"disk\" id=\"a\"/>\n</scene>\n").find("/e.xml:2:33: id 'a' is used twice") != std::string::npos);
  CHECK(loadError(dir, head + "</scene>\n").find("/e.xml:1:1: the scene has no shape") != std::string::npos);
}

TEST_CASE("mitsuba: the film's rfilter becomes render.filter" * doctest::test_suite("cpu mitsuba")) {
  TempDir dir;
  const auto withFilter = [&](const std::string& rfilter) {
    return load(dir, "<sensor type=\"perspective\"><film type=\"hdrfilm\">" + rfilter + "</film></sensor>\n" + kRect)
        .render.filter;
  };
  CHECK(withFilter("") == montecl::PixelFilter{});  // no rfilter: montecl's box
  CHECK(withFilter("<rfilter type=\"box\"/>") == montecl::PixelFilter{});
  CHECK(montecl::filterText(withFilter("<rfilter type=\"tent\"/>")) == "triangle,radius=1");
  CHECK(montecl::filterText(withFilter("<rfilter type=\"gaussian\"><float name=\"stddev\" value=\"0.25\"/></rfilter>")) ==
        "gaussian,radius=1,sigma=0.25");  // Mitsuba's radius: 4 standard deviations
  const montecl::PixelFilter cr = withFilter("<rfilter type=\"catmullrom\"/>");
  CHECK(cr.type == montecl::FilterType::Mitchell);
  CHECK(cr.b == 0.0f);
  CHECK(cr.c == 0.5f);
  CHECK(montecl::filterText(withFilter("<rfilter type=\"lanczos\"><integer name=\"lobes\" value=\"2\"/></rfilter>")) ==
        "lanczos,radius=2,tau=2");
  std::vector<std::string> warnings;
  load(dir, "<sensor type=\"perspective\"><film type=\"hdrfilm\"><rfilter type=\"frob\"/></film></sensor>\n" + std::string(kRect),
       &warnings);
  CHECK(std::any_of(warnings.begin(), warnings.end(),
                    [](const std::string& w) { return w.find("rfilter \"frob\"") != std::string::npos; }));
}

}  // namespace test_file_mitsuba_parser
