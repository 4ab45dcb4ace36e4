// test_gltf_draco.cpp: KHR_draco_mesh_compression through the glTF loader, on files the Draco
// encoder library writes here (tests/fixtures/mesh_files.h) from the float tent model: lossless
// Draco loads to the float file's triangles and renders bit for bit as it; quantized Draco stays
// within the quantization step, in vertices and in the depth AOV; a truncated or corrupt buffer,
// an accessor count or attribute id that disagrees with the buffer are one line naming the
// primitive (exit 2 through the command line), never a crash. And the tinygltf the tests run is
// Debian's library, not the copy inside libdraco (CMakeLists.txt: the link order).
#include <dlfcn.h>
#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <tuple>
#include <vector>

#include "cli_runner.h"
#include "image/exr_layers.h"
#include "mesh_files.h"
#include "scene/gltf_model.h"
#include "scene/mesh_loaders.h"
#include "scene/scene.h"
#include "util/errors.h"

namespace test_file_gltf_draco {  // keeps this file's helpers apart in a unity batch

using montecl::Scene;
using montecl_test::TempDir;
using nlohmann::json;

namespace {

const char* const kPrimitive = "meshes[0].primitives[0]";

Scene loadText(const TempDir& dir, const std::string& name, const std::string& text, std::vector<std::string>* warnings = nullptr) {
  dir.write(name, text);
  Scene s;
  std::vector<std::string> w;
  montecl::loadGltfInto(dir.file(name), s, warnings ? warnings : &w, nullptr);
  return s;
}

// The loader's message for a file, "" when it loads.
std::string errorOf(const TempDir& dir, const json& g) {
  try {
    loadText(dir, "bad.gltf", g.dump());
  } catch (const montecl::InputError& e) {
    return e.what();
  }
  return "";
}

// The Draco buffer's bytes (the data URI of buffer 0) and a file whose buffer holds other bytes.
std::string dracoBytes(const json& g) {
  const std::string uri = g["buffers"][0]["uri"], prefix = "data:application/octet-stream;base64,";
  static const std::string alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  std::uint32_t acc = 0;
  int bits = 0;
  for (std::size_t i = prefix.size(); i < uri.size() && uri[i] != '='; ++i) {
    acc = (acc << 6) | std::uint32_t(alphabet.find(uri[i]));
    bits += 6;
    if (bits >= 8) out += char((acc >> (bits -= 8)) & 0xff);
  }
  return out;
}
json withBytes(json g, const std::string& bytes) {
  g["buffers"][0]["uri"] = "data:application/octet-stream;base64," + montecl_test::base64(bytes);
  g["buffers"][0]["byteLength"] = bytes.size();
  g["bufferViews"][0]["byteLength"] = bytes.size();
  return g;
}

// The same file as a .glb: the Draco buffer in the BIN chunk (4-byte aligned chunks).
std::string glbOf(json g) {
  std::string bin = dracoBytes(g);
  g["buffers"][0].erase("uri");
  std::string text = g.dump();
  while (text.size() % 4) text += ' ';
  while (bin.size() % 4) bin += '\0';
  const auto u32 = [](std::size_t v) {
    const std::uint32_t x = static_cast<std::uint32_t>(v);
    return std::string(reinterpret_cast<const char*>(&x), 4);
  };
  return "glTF" + u32(2) + u32(28 + text.size() + bin.size()) + u32(text.size()) + "JSON" + text + u32(bin.size()) +
         std::string("BIN\0", 4) + bin;
}

// A fixed camera on the tent (a bare mesh would be framed by its bounds, which quantization moves).
std::string sceneFor(const std::string& mesh) {
  return R"({"camera":{"position":[1.25,2.2,1.3],"target":[1.25,0.3,-1],"up":[0,1,0],"fov_y":45,"width":48,"height":32},)"
         R"("meshes":[{"file":")" + mesh + R"("}],"render":{"integrator":"ao","spp":4,"seed":3,"ao_distance":1.0,"background":[0,0,0]}})";
}

montecl::LayeredImage render(const TempDir& dir, const std::string& mesh, const std::string& text) {
  dir.write(mesh, text);
  dir.write(mesh + ".json", sceneFor(mesh));
  const montecl_test::CliResult r =
      montecl_test::runMontecl({"render", dir.file(mesh + ".json"), "-o", dir.file(mesh + ".exr"), "--aov", "all", "-q"});
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  return montecl::readLayeredImage(dir.file(mesh + ".exr"));
}

}  // namespace

TEST_CASE("glTF Draco: tinygltf's functions come from libtinygltf, not from libdraco's copy of it" *
          doctest::test_suite("cpu")) {
  Dl_info info{};
  REQUIRE(dladdr(reinterpret_cast<void*>(&tinygltf::IsDataURI), &info) != 0);
  REQUIRE(info.dli_fname != nullptr);
  CHECK(std::string(info.dli_fname).find("libtinygltf") != std::string::npos);
}

TEST_CASE("glTF Draco, lossless (.gltf and .glb): exactly the float file's triangles, normals and UVs" * doctest::test_suite("cpu")) {
  TempDir dir;
  const montecl_test::MeshData tent = montecl_test::tentMesh();
  std::vector<std::string> warnings;
  const Scene ref = loadText(dir, "float.gltf", montecl_test::gltfText(tent, 0.5f, ""));
  const std::string text = montecl_test::gltfDracoText(tent, 0.5f, 0);
  REQUIRE(ref.triangles.size() == 4);
  for (const bool glb : {false, true}) {
    CAPTURE(glb);
    const Scene d = glb ? loadText(dir, "draco.glb", glbOf(json::parse(text)), &warnings)
                        : loadText(dir, "draco.gltf", text, &warnings);
    CHECK(warnings.empty());  // a supported extension: nothing to say
    REQUIRE(d.triangles.size() == ref.triangles.size());
    for (std::size_t i = 0; i < d.triangles.size(); ++i)
      for (int k = 0; k < 3; ++k) {
        CAPTURE(i);
        CAPTURE(k);
        CHECK(d.triangles[i].v[k] == ref.triangles[i].v[k]);
        CHECK(d.triangles[i].n[k] == ref.triangles[i].n[k]);
        CHECK(d.triangles[i].uv[k] == ref.triangles[i].uv[k]);
        CHECK(d.triangles[i].attributes == ref.triangles[i].attributes);
      }
  }
}

TEST_CASE("glTF Draco, quantized (edgebreaker): every vertex within half a quantization step of the float model's" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  const montecl_test::MeshData tent = montecl_test::tentMesh();
  const Scene ref = loadText(dir, "float.gltf", montecl_test::gltfText(tent, 0.5f, ""));
  for (int bits : {8, 11, 14}) {
    CAPTURE(bits);
    const Scene d = loadText(dir, "draco.gltf", montecl_test::gltfDracoText(tent, 0.5f, bits));
    REQUIRE(d.triangles.size() == ref.triangles.size());
    // Draco quantizes positions on a cube of the largest extent (the tent's x: 2.5).
    const float half = 0.5f * 2.5f / float((1 << bits) - 1) * 1.0001f;
    // The faces come in another order, each rotated: matched by a corner within the step.
    std::vector<bool> used(ref.triangles.size(), false);
    for (const montecl::SceneTriangle& t : d.triangles) {
      bool found = false;
      for (std::size_t r = 0; r < ref.triangles.size() && !found; ++r)
        for (int rot = 0; rot < 3 && !found && !used[r]; ++rot) {
          bool all = true;
          for (int k = 0; k < 3; ++k) {
            const glm::vec3 e = glm::abs(t.v[k] - ref.triangles[r].v[(k + rot) % 3]);
            all = all && e.x <= half && e.y <= half && e.z <= half;
          }
          if (all) found = used[r] = true;
        }
      INFO(t.v[0].x << " " << t.v[0].y << " " << t.v[0].z);
      CHECK(found);
    }
  }
}

TEST_CASE("glTF Draco renders: lossless bit for bit as the float file; quantized depth within the step away from edges" *
          doctest::test_suite("cli sanitize")) {
  TempDir dir;
  const montecl_test::MeshData tent = montecl_test::tentMesh();
  const montecl::LayeredImage ref = render(dir, "float.gltf", montecl_test::gltfText(tent, 0.5f, ""));
  const montecl::LayeredImage lossless = render(dir, "draco.gltf", montecl_test::gltfDracoText(tent, 0.5f, 0));
  REQUIRE(lossless.channels == ref.channels);
  for (std::size_t c = 0; c < ref.channels.size(); ++c) {
    CAPTURE(ref.channels[c]);
    CHECK(lossless.planes[c] == ref.planes[c]);
  }
  // 11 bits on the tent's 2.5: a step of 1.2e-3. A vertex moved by half a step moves a surface the
  // camera sees at an angle by a few steps along the ray; pixels next to a depth edge or a miss
  // may change what they see and are left out.
  const montecl::LayeredImage q = render(dir, "draco11.gltf", montecl_test::gltfDracoText(tent, 0.5f, 11));
  const std::vector<float>&zr = *ref.find("Z"), &zq = *q.find("Z");
  const int w = ref.width, h = ref.height;
  const float step = 2.5f / 2047.0f;
  int compared = 0, within = 0;
  for (int y = 1; y + 1 < h; ++y)
    for (int x = 1; x + 1 < w; ++x) {
      // An edge: a miss in the 3x3 neighbourhood, or depth that does not run on smoothly (a
      // second difference across the pixel, which a plane keeps near 0).
      const auto at = [&](int dx, int dy) { return zr[std::size_t((y + dy) * w + x + dx)]; };
      const float z = at(0, 0);
      bool edge = std::fabs(at(-1, 0) + at(1, 0) - 2.0f * z) > 0.05f || std::fabs(at(0, -1) + at(0, 1) - 2.0f * z) > 0.05f;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) edge = edge || !(at(dx, dy) > 0.0f);
      if (edge) continue;
      ++compared;
      const float dz = std::fabs(zq[std::size_t(y * w + x)] - z);
      within += dz <= 4.0f * step;
      if (dz > 4.0f * step) MESSAGE("pixel " << x << "," << y << ": " << z << " vs " << zq[std::size_t(y * w + x)]);
    }
  MESSAGE(compared << " of " << w * h << " pixels compared");
  CHECK(compared > w * h / 6);  // the tent and the floor inside its edges: a fifth of the picture
  CHECK(within == compared);
}

TEST_CASE("glTF Draco: every truncation of the buffer and corrupt bytes are one line naming the primitive, never a crash" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  const json g = json::parse(montecl_test::gltfDracoText(montecl_test::tentMesh(), 0.5f, 11));
  const std::string bytes = dracoBytes(g);
  REQUIRE(bytes.compare(0, 5, "DRACO") == 0);
  REQUIRE(errorOf(dir, g).empty());
  const std::string where = dir.file("bad.gltf") + ": " + kPrimitive + ".extensions.KHR_draco_mesh_compression: ";
  int refused = 0;
  for (std::size_t n = 0; n < bytes.size(); ++n) {
    CAPTURE(n);
    json cut = g;
    cut["bufferViews"][0]["byteLength"] = n;  // the view ends early; the buffer is whole
    const std::string e = errorOf(dir, cut);
    if (e.empty()) continue;  // the tail held nothing the decoder needed
    ++refused;
    CHECK(e.find(where + "Draco buffer (bufferView 0) cannot be decoded: ") == 0);
    CHECK(e.find('\n') == std::string::npos);
  }
  CHECK(refused >= int(bytes.size()) * 9 / 10);
  // Bytes overwritten: the header's magic, and every byte after it flipped in turn.
  std::string bad = bytes;
  bad[0] = 'X';
  CHECK(errorOf(dir, withBytes(g, bad)) == where + "Draco buffer (bufferView 0) cannot be decoded: Not a Draco file");
  for (std::size_t i = 5; i < bytes.size(); ++i) {
    bad = bytes;
    bad[i] = char(~bad[i]);
    const std::string e = errorOf(dir, withBytes(g, bad));  // decoded to something else, or refused
    CHECK(e.find('\n') == std::string::npos);
    if (!e.empty()) CHECK(e.find(dir.file("bad.gltf") + ": ") == 0);
  }
}

TEST_CASE("glTF Draco: an accessor count, id or type that disagrees with the buffer is one line naming it" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  const json g = json::parse(montecl_test::gltfDracoText(montecl_test::tentMesh(), 0.5f, 0));
  const std::string file = dir.file("bad.gltf") + ": " + kPrimitive;
  const std::string ext = file + ".extensions.KHR_draco_mesh_compression";
  json c = g;
  c["accessors"][0]["count"] = 7;
  CHECK(errorOf(dir, c) == ext + ".attributes.POSITION: accessor 0 says 7 elements, the Draco buffer decodes 6 points");
  c = g;
  c["accessors"][3]["count"] = 9;
  CHECK(errorOf(dir, c) == file + ".indices: accessor 3 says 9 indices, the Draco buffer decodes 4 triangles");
  c = g;
  c["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["attributes"]["NORMAL"] = 9;
  CHECK(errorOf(dir, c) == ext + ".attributes.NORMAL: the Draco buffer has no attribute with id 9");
  c = g;
  c["accessors"][2]["type"] = "VEC3";
  CHECK(errorOf(dir, c) == ext + ".attributes.TEXCOORD_0: accessor 2 has 3 components per element, the Draco attribute 2");
  c = g;
  c["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["attributes"]["COLOR_0"] = 0;
  CHECK(errorOf(dir, c) == ext + ".attributes.COLOR_0: names COLOR_0, which the primitive's attributes do not have");
  c = g;
  c["meshes"][0]["primitives"][0]["mode"] = 5;
  CHECK(errorOf(dir, c) == file + ": mode 5 with KHR_draco_mesh_compression: a Draco mesh is a list of triangles (mode 4)");
  c = g;
  c["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["bufferView"] = 4;
  CHECK(errorOf(dir, c) == ext + ".bufferView: bufferView 4 out of range");
  // A NORMAL accessor of a component type glTF does not allow for normals: the same rule as plain accessors.
  c = g;
  c["accessors"][1]["componentType"] = 5121;
  CHECK(errorOf(dir, c).find(file + ".NORMAL: expected FLOAT or (KHR_mesh_quantization) normalized signed") == 0);
}

TEST_CASE("glTF Draco through the command line: a truncated buffer and a disagreeing count exit 2 with one line" *
          doctest::test_suite("cli sanitize")) {
  TempDir dir;
  const json g = json::parse(montecl_test::gltfDracoText(montecl_test::tentMesh(), 0.5f, 11));
  json cut = g, count = g;
  cut["bufferViews"][0]["byteLength"] = 20;
  count["accessors"][0]["count"] = 5;
  for (const auto& row : {std::tuple<const char*, json, const char*>{"cut.gltf", cut, "cannot be decoded"},
                                         {"count.gltf", count, "the Draco buffer decodes"}}) {
    const auto& name = std::get<0>(row);
    const auto& file = std::get<1>(row);
    const auto& what = std::get<2>(row);
    CAPTURE(name);
    dir.write(name, file.dump());
    const montecl_test::CliResult r = montecl_test::runMontecl({"render", dir.file(name), "-o", dir.file("x.png"), "-q"});
    INFO(r.err);
    CHECK(r.exitCode == 2);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK(r.err.find(dir.file(name) + ": " + kPrimitive) != std::string::npos);
    CHECK(r.err.find(what) != std::string::npos);
    CHECK(!montecl_test::readAll(dir.file("x.png")).size());
  }
}

}  // namespace test_file_gltf_draco
