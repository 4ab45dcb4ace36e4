// test_provenance.cpp: a render's provenance in its EXR header (image/provenance.h,
// scene/scene_digest.h) and `montecl merge` refusing what must not be merged: the same samples
// twice, other scenes, other settings, renders without provenance; --force merges anyway.
#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>

#include "cli_runner.h"
#include "image/exr_layers.h"
#include "image/provenance.h"
#include "scene/scene.h"
#include "scene/scene_digest.h"
#include "util/errors.h"

namespace test_file_provenance {  // keeps this file's helpers apart in a unity batch

using namespace montecl;
using namespace montecl_test;  // runMontecl, renderOnHost, oneLine, TempDir, ... (fixtures/cli_runner.h)
namespace fs = std::filesystem;

namespace {

LayeredImage tiny(const Provenance* p) {
  LayeredImage im;
  im.width = 2;
  im.height = 1;
  for (const char* c : {"R", "G", "B", "samples"}) im.set(c, {1.0f, 2.0f});
  if (p) setProvenance(im, *p);
  return im;
}

Provenance prov(std::vector<SampleRange> ranges, std::string scene = "aaaa", std::string settings = "integrator=ao") {
  return Provenance{"0.14.0", scene, settings, "off", std::move(ranges)};
}

std::string mergeError(const std::vector<Provenance>& ps) {
  std::vector<LayeredImage> images;
  std::vector<std::string> names;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    images.push_back(tiny(&ps[i]));
    names.push_back("r" + std::to_string(i) + ".exr");
  }
  try {
    mergeProvenance(images, names, false);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::vector<std::string> renderArgs(const std::string& scene, const std::string& out, int spp, int first,
                                    std::vector<std::string> extra = {}) {
  std::vector<std::string> args{"render", scene, "-o", out, "--width", "24", "--height", "16", "--spp",
                                std::to_string(spp), "--first-sample", std::to_string(first), "-q"};
  args.insert(args.end(), extra.begin(), extra.end());
  return args;
}

const std::string kQuad = std::string(MONTECL_SOURCE_DIR) + "/scenes/test/good/scene.json";

}  // namespace

TEST_CASE("provenance: sample ranges format and parse; malformed ones are refused" * doctest::test_suite("cpu")) {
  std::vector<SampleRange> r = {{0, 0, 64}, {7, 128, 192}};
  CHECK(formatSampleRanges(r) == "0:0-64,7:128-192");
  auto back = parseSampleRanges("0:0-64,7:128-192");
  REQUIRE(back);
  CHECK(formatSampleRanges(*back) == "0:0-64,7:128-192");
  for (const char* bad : {"", "0:5-5", "0:9-3", "x:0-1", "0:0", "0-1", "4294967296:0-1", "0:0-1,", "0:-1-2"})
    CHECK_MESSAGE(!parseSampleRanges(bad), std::string(bad));
  LayeredImage im = tiny(nullptr);
  CHECK(!readProvenance(im, "old.exr"));
  im.attributes["montecl:scene"] = "aaaa";
  im.attributes["montecl:samples"] = "zero";
  CHECK_THROWS_AS(readProvenance(im, "old.exr"), InputError);
}

TEST_CASE("provenance: merge refuses overlapping samples of one seed, other scenes, other settings, none" * doctest::test_suite("cpu")) {
  CHECK(mergeError({prov({{0, 0, 16}}), prov({{0, 16, 32}})}).empty());
  CHECK(mergeError({prov({{1, 0, 16}}), prov({{2, 0, 16}})}).empty());  // other seeds: other samples
  std::string e = mergeError({prov({{0, 0, 16}}), prov({{0, 8, 24}})});
  CHECK(e.find("r1.exr") == 0);
  CHECK(e.find("overlap") != std::string::npos);
  CHECK(e.find("r0.exr") != std::string::npos);
  CHECK(e.find("--force") != std::string::npos);
  CHECK(mergeError({prov({{0, 0, 16}}), prov({{3, 0, 4}, {0, 15, 16}})}).find("overlap") != std::string::npos);
  e = mergeError({prov({{0, 0, 16}}), prov({{0, 16, 32}}, "bbbb")});
  CHECK(e.find("r1.exr") == 0);
  CHECK(e.find("scene") != std::string::npos);
  e = mergeError({prov({{0, 0, 16}}), prov({{0, 16, 32}}, "aaaa", "integrator=direct")});
  CHECK(e.find("r1.exr") == 0);
  CHECK(e.find("settings") != std::string::npos);

  std::vector<LayeredImage> withOld = {tiny(nullptr)};
  withOld.push_back(tiny(nullptr));
  Provenance p0 = prov({{0, 0, 16}});
  withOld[1] = tiny(&p0);
  CHECK_THROWS_WITH_AS(mergeProvenance(withOld, {"old.exr", "new.exr"}, false),
                       doctest::Contains("old.exr: no montecl provenance"), InputError);
  CHECK(!mergeProvenance(withOld, {"old.exr", "new.exr"}, true));  // forced: the output claims nothing

  // The union: sorted, touching ranges of a seed joined.
  Provenance a = prov({{0, 16, 32}}), b = prov({{0, 0, 16}, {5, 0, 8}}), c = prov({{0, 40, 48}});
  auto u = mergeProvenance({tiny(&a), tiny(&b), tiny(&c)}, {}, false);
  REQUIRE(u);
  CHECK(formatSampleRanges(u->samples) == "0:0-32,0:40-48,5:0-8");
  CHECK(u->scene == "aaaa");
  // Forced past an overlap and another scene: both listed, so later merges see them.
  Provenance d = prov({{0, 8, 24}}, "bbbb");
  auto f = mergeProvenance({tiny(&a), tiny(&d)}, {}, true);
  REQUIRE(f);
  CHECK(formatSampleRanges(f->samples) == "0:8-24,0:16-32");
  CHECK(f->scene == "aaaa | bbbb");
}

TEST_CASE("provenance: the scene digest follows content, not paths or image size" * doctest::test_suite("cpu")) {
  Scene s;
  s.path = "a/scene.json";
  s.materials.push_back({"m", glm::vec3(0.5f), glm::vec3(0.0f)});
  s.triangles.push_back({{glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0)}, 0});
  const std::string d = sceneDigest(s);
  CHECK(d.size() == 16);
  Scene t = s;
  t.path = "b/other.json";
  t.camera.width = 99;
  t.render.spp = 3;
  CHECK(sceneDigest(t) == d);
  t = s;
  t.triangles[0].v[2].y = 1.0001f;
  CHECK(sceneDigest(t) != d);
  t = s;
  t.materials[0].emission.x = 1.0f;
  CHECK(sceneDigest(t) != d);
  t = s;
  t.camera.fovY = 40.0f;
  CHECK(sceneDigest(t) != d);
  t = s;  // a conductor's distribution and factor are part of what it renders
  t.materials[0].kind = MCL_MATERIAL_conductor;
  const std::string conductor = sceneDigest(t);
  t.materials[0].beckmann = true;
  CHECK(sceneDigest(t) != conductor);
  t.materials[0].beckmann = false;
  t.materials[0].conductorFactor = glm::vec3(0.3f);
  const std::string factor = sceneDigest(t);
  CHECK(factor != conductor);
  t.materials[0].conductorFactor = glm::vec3(0.4f);
  CHECK(sceneDigest(t) != factor);
  RenderSettings r;
  RenderSettings r2 = r;
  r2.aoSampling = AoSampling::Uniform;
  CHECK(integratorSettings(r) != integratorSettings(r2));
  r2 = r;
  r2.seed = 5;
  r2.spp = 1;
  CHECK(integratorSettings(r) == integratorSettings(r2));
}

TEST_CASE("provenance: string attributes survive an EXR write and read" * doctest::test_suite("cpu")) {
  TempDir dir;
  Provenance p = prov({{3, 5, 8}});
  LayeredImage im = tiny(&p);
  im.attributes["other"] = "not montecl's";
  writeLayeredExr(dir.file("p.exr"), im);
  LayeredImage back = readLayeredImage(dir.file("p.exr"));
  auto q = readProvenance(back, "p.exr");
  REQUIRE(q);
  CHECK(q->scene == "aaaa");
  CHECK(q->settings == "integrator=ao");
  CHECK(q->version == "0.14.0");
  CHECK(formatSampleRanges(q->samples) == "3:5-8");
  CHECK(back.attributes.count("other") == 0);  // only montecl:* are read
}

TEST_CASE("cli: a render's EXR header holds its provenance" * doctest::test_suite("cli sanitize")) {
  TempDir dir;
  REQUIRE(runMontecl(renderArgs(montecl_test::demoScene(), dir.file("r.exr"), 3, 5, {"--seed", "7"})).exitCode == 0);
  LayeredImage im = readLayeredImage(dir.file("r.exr"));
  auto p = readProvenance(im, "r.exr");
  REQUIRE(p);
  CHECK(p->version == MONTECL_VERSION);
  CHECK(p->scene.size() == 16);
  CHECK(formatSampleRanges(p->samples) == "7:5-8");
  CHECK(p->settings.find("integrator=ao") == 0);
  CHECK(p->adaptive == "off");
  REQUIRE(runMontecl(renderArgs(montecl_test::demoScene(), dir.file("ad.exr"), 3, 0,
                                {"--target-error", "0.5", "--min-spp", "4", "--max-spp", "8"}))
              .exitCode == 0);
  auto ad = readProvenance(readLayeredImage(dir.file("ad.exr")), "ad.exr");
  REQUIRE(ad);
  CHECK(formatSampleRanges(ad->samples) == "0:0-8");  // all an adaptive render may take
  CHECK(ad->adaptive.find("max_spp=8") != std::string::npos);
}

TEST_CASE("cli: merge refuses the same render twice, other scenes, other settings, renders without provenance; --force merges" * doctest::test_suite("cli sanitize")) {
  TempDir dir;
  const std::string demo = montecl_test::demoScene();
  REQUIRE(runMontecl(renderArgs(demo, dir.file("a.exr"), 4, 0)).exitCode == 0);
  REQUIRE(runMontecl(renderArgs(demo, dir.file("b.exr"), 4, 4)).exitCode == 0);
  REQUIRE(runMontecl(renderArgs(demo, dir.file("ab.exr"), 6, 2)).exitCode == 0);      // overlaps both
  REQUIRE(runMontecl(renderArgs(kQuad, dir.file("quad.exr"), 4, 4)).exitCode == 0);   // another scene
  REQUIRE(runMontecl(renderArgs(demo, dir.file("uni.exr"), 4, 4, {"--ao-sampling", "uniform"})).exitCode == 0);
  LayeredImage old = readLayeredImage(dir.file("b.exr"));
  old.attributes.clear();  // as montecl wrote it before provenance existed
  writeLayeredExr(dir.file("old.exr"), old);

  struct Case {
    std::string second, expect;
  };
  for (const Case& c : {Case{"a.exr", "overlap"}, Case{"ab.exr", "overlap"}, Case{"quad.exr", "another scene"},
                        Case{"uni.exr", "other settings"}, Case{"old.exr", "no montecl provenance"}}) {
    INFO("merge a.exr " << c.second);
    CliResult r = runMontecl({"merge", dir.file("a.exr"), dir.file(c.second), "-o", dir.file("m.exr")});
    CHECK(r.exitCode == 2);
    CHECK(oneLine(r.err));
    CHECK(r.err.find(c.second) != std::string::npos);
    CHECK(r.err.find(c.expect) != std::string::npos);
    CHECK(!fs::exists(dir.file("m.exr")));
    CliResult forced = runMontecl({"merge", dir.file("a.exr"), dir.file(c.second), "-o", dir.file("f.exr"), "--force"});
    CHECK(forced.exitCode == 0);
  }

  // A clean split merges, and the result carries the union, which later merges are checked against.
  REQUIRE(runMontecl({"merge", dir.file("a.exr"), dir.file("b.exr"), "-o", dir.file("m.exr"), "-q"}).exitCode == 0);
  auto m = readProvenance(readLayeredImage(dir.file("m.exr")), "m.exr");
  REQUIRE(m);
  CHECK(formatSampleRanges(m->samples) == "0:0-8");
  CliResult again = runMontecl({"merge", dir.file("m.exr"), dir.file("b.exr"), "-o", dir.file("m2.exr")});
  CHECK(again.exitCode == 2);
  CHECK(again.err.find("overlap") != std::string::npos);
  REQUIRE(runMontecl(renderArgs(demo, dir.file("c.exr"), 4, 8)).exitCode == 0);
  REQUIRE(runMontecl({"merge", dir.file("m.exr"), dir.file("c.exr"), "-o", dir.file("m3.exr"), "-q"}).exitCode == 0);
  auto m3 = readProvenance(readLayeredImage(dir.file("m3.exr")), "m3.exr");
  REQUIRE(m3);
  CHECK(formatSampleRanges(m3->samples) == "0:0-12");
}

}  // namespace test_file_provenance
