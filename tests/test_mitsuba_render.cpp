// test_mitsuba_render.cpp: Mitsuba scene files and the table of readers through the real command
// line: the same Cornell box as montecl JSON (OBJ + MTL) and as Mitsuba XML (the same OBJs, the
// JSON's values written as XML) renders bit for bit the same image (and one changed value does
// not); a malformed file exits 2 with one file:line:column line; an unsupported plugin warns and
// the render goes on; a file of another kind names the formats montecl reads.
#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "cli_runner.h"
#include "scene/scene_readers.h"

namespace test_file_mitsuba_render {  // keeps this file's helpers apart in a unity batch

using montecl_test::CliResult;
using montecl_test::readAll;
using montecl_test::runMontecl;
using montecl_test::TempDir;

namespace {

std::size_t lineCount(const std::string& text) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < text.size(); ++i)
    if (text[i] == '\n' || i + 1 == text.size()) ++n;
  return n;
}

struct Part {
  const char* name;
  const char* quads;  // the OBJ's corners, 4 per face
  const char* kd;
  const char* ke;  // "" for none
};

// A Cornell box in 1-unit walls: floor, ceiling, back, left (red), right (green), a short block
// and the light under the ceiling (facing down).
const Part kParts[] = {
    {"floor", "-1 0 -1  -1 0 1  1 0 1  1 0 -1", "0.725 0.71 0.68", ""},
    {"ceiling", "-1 2 -1  1 2 -1  1 2 1  -1 2 1", "0.725 0.71 0.68", ""},
    {"back", "-1 0 -1  1 0 -1  1 2 -1  -1 2 -1", "0.725 0.71 0.68", ""},
    {"left", "-1 0 -1  -1 2 -1  -1 2 1  -1 0 1", "0.63 0.065 0.05", ""},
    {"right", "1 0 -1  1 0 1  1 2 1  1 2 -1", "0.14 0.45 0.091", ""},
    {"block", "-0.5 0.6 -0.3  -0.1 0.6 -0.3  -0.1 0.6 0.1  -0.5 0.6 0.1", "0.725 0.71 0.68", ""},
    {"light", "-0.25 1.98 -0.25  0.25 1.98 -0.25  0.25 1.98 0.25  -0.25 1.98 0.25", "0 0 0", "17 12 4"},
};

void writeBox(const TempDir& dir) {
  for (const Part& p : kParts) {
    std::string corners = p.quads, obj = std::string("mtllib ") + p.name + ".mtl\nusemtl m\nv ";
    for (std::size_t i = 0; i < corners.size(); ++i) obj += corners.compare(i, 2, "  ") == 0 ? (++i, "\nv ") : std::string(1, corners[i]);
    dir.write(std::string(p.name) + ".obj", obj + "\nf 1 2 3 4\n");
    dir.write(std::string(p.name) + ".mtl",
              std::string("newmtl m\nKd ") + p.kd + "\n" + (*p.ke ? std::string("Ke ") + p.ke + "\n" : std::string()));
  }
}

std::string boxJson() {
  std::string meshes;
  for (const Part& p : kParts) meshes += std::string(meshes.empty() ? "" : ", ") + "{\"file\": \"" + p.name + ".obj\"}";
  return "{\"camera\": {\"position\": [0, 1, 3.9], \"target\": [0, 1, 0], \"up\": [0, 1, 0], \"fov_y\": 39.3, "
         "\"width\": 24, \"height\": 20},\n \"meshes\": [" + meshes + "],\n"
         " \"render\": {\"integrator\": \"path\", \"spp\": 8, \"seed\": 3, \"max_depth\": -1, \"rr_depth\": 5, "
         "\"sampler\": \"independent\"}}\n";
}

// The JSON's values as Mitsuba XML: the same OBJs, each with its MTL's Kd as a two-sided diffuse
// BSDF and its Ke as an area emitter. `leftRed`: the left wall's red (0.63 in the JSON).
std::string boxXml(const std::string& leftRed = "0.63") {
  std::string shapes;
  for (const Part& p : kParts) {
    std::string kd = p.kd;
    if (std::string(p.name) == "left") kd = leftRed + " 0.065 0.05";
    shapes += std::string("  <shape type=\"obj\"><string name=\"filename\" value=\"") + p.name + ".obj\"/>\n"
              "    <bsdf type=\"twosided\"><bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"" + kd + "\"/></bsdf></bsdf>\n" +
              (*p.ke ? std::string("    <emitter type=\"area\"><rgb name=\"radiance\" value=\"") + p.ke + "\"/></emitter>\n" : "") +
              "  </shape>\n";
  }
  return "<scene version=\"3.0.0\">\n  <default name=\"spp\" value=\"8\"/>\n"
         "  <integrator type=\"path\"><integer name=\"max_depth\" value=\"-1\"/><integer name=\"rr_depth\" value=\"5\"/></integrator>\n"
         "  <sensor type=\"perspective\">\n    <float name=\"fov\" value=\"39.3\"/><string name=\"fov_axis\" value=\"y\"/>\n"
         "    <transform name=\"to_world\"><lookat origin=\"0, 1, 3.9\" target=\"0, 1, 0\" up=\"0, 1, 0\"/></transform>\n"
         "    <sampler type=\"independent\"><integer name=\"sample_count\" value=\"$spp\"/><integer name=\"seed\" value=\"3\"/></sampler>\n"
         "    <film type=\"hdrfilm\"><integer name=\"width\" value=\"24\"/><integer name=\"height\" value=\"20\"/>"
         "<rfilter type=\"box\"/></film>\n  </sensor>\n" + shapes + "</scene>\n";
}

CliResult render(const TempDir& dir, const std::string& scene, const std::string& out) {
  return runMontecl({"render", dir.file(scene), "-q", "--device", "host", "-o", dir.file(out)});
}

}  // namespace

TEST_CASE("mitsuba cli: the same Cornell box as montecl JSON and as Mitsuba XML renders bit for bit the same" *
          doctest::test_suite("cli mitsuba")) {
  TempDir dir;
  writeBox(dir);
  dir.write("box.json", boxJson());
  dir.write("box.xml", boxXml());
  dir.write("changed.xml", boxXml("0.64"));
  const CliResult a = render(dir, "box.json", "json.pfm");
  const CliResult b = render(dir, "box.xml", "xml.pfm");
  const CliResult c = render(dir, "changed.xml", "changed.pfm");
  INFO("json: " << a.err << "\nxml: " << b.err << "\nchanged: " << c.err);
  REQUIRE(a.exitCode == 0);
  REQUIRE(b.exitCode == 0);
  REQUIRE(c.exitCode == 0);
  CHECK(b.err.empty());  // every tag of this file is read: no warning
  const std::string json = readAll(dir.file("json.pfm")), xml = readAll(dir.file("xml.pfm"));
  REQUIRE(json.size() > 24 * 20 * 12);
  CHECK(json == xml);
  CHECK(readAll(dir.file("changed.pfm")) != json);  // the comparison sees one changed reflectance
}

TEST_CASE("mitsuba cli: malformed XML exits 2 with one line naming file:line:column" * doctest::test_suite("cli mitsuba sanitize")) {
  TempDir dir;
  dir.write("bad.xml", "<scene version=\"3.0.0\">\n  <shape type=\"rectangle\">\n    <float name=\"x\" value=\"1\">\n</scene>\n");
  CliResult r = render(dir, "bad.xml", "out.png");
  INFO("stderr: " << r.err);
  CHECK(r.exitCode == 2);
  CHECK(lineCount(r.err) == 1);
  CHECK(r.err.find("bad.xml:4:3: malformed XML") != std::string::npos);
  // A bad value: its element's line and column.
  dir.write("value.xml", "<scene version=\"3.0.0\">\n  <shape type=\"sphere\">\n     <float name=\"radius\" value=\"big\"/>\n"
                         "  </shape>\n</scene>\n");
  r = render(dir, "value.xml", "out.png");
  CHECK(r.exitCode == 2);
  CHECK(lineCount(r.err) == 1);
  CHECK(r.err.find("value.xml:3:6:") != std::string::npos);
  CHECK(r.err.find("not a list of numbers") != std::string::npos);
}

TEST_CASE("mitsuba cli: an unsupported plugin warns with file:line:column and the render goes on" * doctest::test_suite("cli mitsuba")) {
  TempDir dir;
  dir.write("s.xml", "<scene version=\"3.0.0\">\n<sensor type=\"perspective\"><film type=\"hdrfilm\"><integer name=\"width\" value=\"8\"/>"
                     "<integer name=\"height\" value=\"8\"/></film></sensor>\n"
                     "<shape type=\"cylinder\"/>\n"
                     "<shape type=\"rectangle\"><transform name=\"to_world\"><translate z=\"3\"/></transform>\n"
                     "  <bsdf type=\"twosided\"><bsdf type=\"diffuse\"/></bsdf><emitter type=\"area\"><rgb name=\"radiance\" value=\"1\"/></emitter></shape>\n"
                     "</scene>\n");
  CliResult r = runMontecl({"render", dir.file("s.xml"), "--device", "host", "--spp", "1", "-o", dir.file("out.png")});
  INFO("stderr: " << r.err);
  CHECK(r.exitCode == 0);
  CHECK(r.err.find("s.xml:3:1: shape \"cylinder\" not read by montecl") != std::string::npos);
  CHECK(readAll(dir.file("out.png")).size() > 0);
}

TEST_CASE("cli: a file montecl cannot read names the formats it reads, from the table of readers" * doctest::test_suite("cli mitsuba sanitize")) {
  TempDir dir;
  dir.write("x.stl", "solid x\nendsolid x\n");
  CliResult r = runMontecl({"render", dir.file("x.stl"), "-q", "-o", dir.file("out.png")});
  INFO("stderr: " << r.err);
  CHECK(r.exitCode == 2);
  CHECK(lineCount(r.err) == 1);
  CHECK(r.err.find("x.stl: montecl reads .json, .obj, .ply, .gltf, .glb, .pbrt, .xml") != std::string::npos);
  CHECK(montecl::readableExtensions() == ".json, .obj, .ply, .gltf, .glb, .pbrt, .xml");
  CHECK(r.err.find("malformed JSON") == std::string::npos);
  // Every row's extension picks its reader: an .xml is read as Mitsuba's (not as JSON).
  dir.write("y.xml", "{ }\n");
  r = runMontecl({"render", dir.file("y.xml"), "-q", "-o", dir.file("out.png")});
  CHECK(r.exitCode == 2);
  CHECK(r.err.find("y.xml:2:1: malformed XML") != std::string::npos);
}

}  // namespace test_file_mitsuba_render
