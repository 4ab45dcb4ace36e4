// test_mtl_alpha.cpp: an MTL map_Kd whose alpha is below 1 somewhere, without map_d, renders
// opaque: one warning names the MTL, the map_Kd line and the ways to cut it out (map_d, the mesh
// entry's alpha_texture), through the real command line; an opaque RGBA texture, an RGB one, or
// the same texture with map_d say nothing.
#include <doctest/doctest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "test_images.h"

namespace test_file_mtl_alpha {  // keeps this file's helpers apart in a unity batch

using namespace montecl_test;  // runMontecl, renderOnHost, oneLine, TempDir, ... (fixtures/cli_runner.h)

namespace {

const char* kQuads =
    "mtllib quads.mtl\nv -1 -1 0\nv 0 -1 0\nv 0 1 0\nv -1 1 0\nv 1 -1 0\nv 1 1 0\n"
    "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl a\nf 1/1 2/2 3/3 4/4\nusemtl b\nf 2/1 5/2 6/3 3/4\n";

CliResult render(const TempDir& dir, const std::vector<std::string>& extra = {}) {
  std::vector<std::string> args{"--overwrite"};
  args.insert(args.end(), extra.begin(), extra.end());
  return renderOnHost(dir.file("quads.obj"), dir.file("out.pfm"), args);
}

std::size_t count(const std::string& s, const std::string& needle) {
  std::size_t n = 0;
  for (std::size_t p = s.find(needle); p != std::string::npos; p = s.find(needle, p + 1)) ++n;
  return n;
}

}  // namespace

TEST_CASE("MTL: an RGBA map_Kd with alpha below 1 and no map_d gets one warning saying how to cut it out" *
          doctest::test_suite("cli sanitize")) {
  TempDir dir;
  dir.write("quads.obj", kQuads);
  // leaf.png: alpha 0 in the left half; opaque.png: RGBA, alpha 255 everywhere; rgb.png: no alpha.
  montecl_test::writeImage8(dir.file("leaf.png"), 4, 4, 4, [](int x, int, int c) { return c == 3 ? (x < 2 ? 0 : 255) : 200; });
  montecl_test::writeImage8(dir.file("opaque.png"), 4, 4, 4, [](int, int, int) { return 255; });
  montecl_test::writeImage8(dir.file("rgb.png"), 4, 4, 3, [](int, int, int) { return 128; });
  dir.write("quads.mtl", "newmtl a\nKd 1 1 1\n\nmap_Kd leaf.png\nnewmtl b\nmap_Kd leaf.png\n");
  const CliResult warned = render(dir);
  INFO(warned.err);
  REQUIRE(warned.exitCode == 0);
  CHECK(count(warned.err, "\n") == 1);
  CHECK(warned.err.find(dir.file("quads.mtl") + ": line 4: material 'a': map_Kd 'leaf.png': the texture's alpha is below 1") !=
        std::string::npos);
  CHECK(warned.err.find("add 'map_d'") != std::string::npos);
  CHECK(warned.err.find("alpha_texture") != std::string::npos);
  CHECK(warned.err.find("(1 more materials like it)") != std::string::npos);
  // Cut out with map_d, or textures whose alpha is all 1 (or absent): nothing to say.
  for (const char* mtl : {"newmtl a\nmap_Kd leaf.png\nmap_d leaf.png\nnewmtl b\nmap_Kd leaf.png\nmap_d leaf.png\n",
                          "newmtl a\nmap_Kd opaque.png\nnewmtl b\nmap_Kd rgb.png\n"}) {
    CAPTURE(mtl);
    dir.write("quads.mtl", mtl);
    const CliResult quiet = render(dir);
    CHECK_MESSAGE(quiet.exitCode == 0, quiet.err);
    CHECK(quiet.err.empty());
  }
}

}  // namespace test_file_mtl_alpha
