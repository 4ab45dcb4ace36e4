// fuzz_entries.cpp: the loaders' fuzz entry points and their seed inputs (see fuzz_entries.h).
#include "fuzz_entries.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <stdexcept>

#include "cl/cache_entry.h"
#include "image/exr_layers.h"
#include "mesh_files.h"
#include "scene/mesh_loaders.h"
#include "scene/scene.h"
#include "util/errors.h"

namespace montecl_fuzz {
namespace fs = std::filesystem;

const char* const kMtlSeparator = "\n#--mtl--\n";

namespace {

std::string readFile(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  if (!in) throw std::runtime_error("fuzz: cannot read " + p.string());
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void writeFile(const fs::path& p, const char* data, std::size_t size) {
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out.write(data, static_cast<std::streamsize>(size));
  out.close();
  if (!out) throw std::runtime_error("fuzz: cannot write " + p.string());
}

void writeFile(const fs::path& p, const std::string& s) { writeFile(p, s.data(), s.size()); }

fs::path sourceDir() { return fs::path(MONTECL_SOURCE_DIR); }

struct Sandbox {
  std::string dir;
  Sandbox() {
    const char* tmp = std::getenv("TMPDIR");
    std::string templ = std::string(tmp && *tmp ? tmp : "/tmp") + "/montecl-fuzz-XXXXXX";
    if (!mkdtemp(&templ[0])) throw std::runtime_error("fuzz: cannot create a temporary folder");
    dir = templ;
    const fs::path good = sourceDir() / "scenes/test/good", demo = sourceDir() / "scenes/demo";
    for (const char* f : {"quad.obj", "quad.mtl"}) fs::copy_file(good / f, fs::path(dir) / f);
    for (const char* f : {"demo.obj", "demo.mtl"}) fs::copy_file(demo / f, fs::path(dir) / f);
    writeFile(fs::path(dir) / "tent.bin", montecl_test::gltfBuffer(montecl_test::tentMesh()));
    writeFile(fs::path(dir) / "wood.png", std::string("not decoded by the loader"));
    writeFile(fs::path(dir) / "tent.ply", montecl_test::plyText(montecl_test::tentMesh(), montecl_test::PlyEncoding::LittleEndian));
    writeFile(fs::path(dir) / "part.pbrt", std::string("Translate 0 1 0\nShape \"disk\" \"float radius\" 0.5\n"));
  }
  ~Sandbox() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
};

// Runs f, mapping montecl's own ways of refusing an input to Rejected; anything else propagates.
template <class F>
Outcome guarded(F&& f) {
  try {
    return f() ? Outcome::Loaded : Outcome::Rejected;
  } catch (const montecl::InputError&) {
    return Outcome::Rejected;
  } catch (const montecl::RuntimeError&) {
    return Outcome::Rejected;
  }
}

std::vector<fs::path> filesNamed(const fs::path& root, const std::string& ext) {
  std::vector<fs::path> out;
  for (const auto& e : fs::recursive_directory_iterator(root))
    if (e.is_regular_file() && e.path().extension() == ext) out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<fs::path> seedRoots() {
  return {sourceDir() / "scenes/test/good", sourceDir() / "scenes/test/bad", sourceDir() / "scenes/demo"};
}

std::vector<std::string> sceneSeeds() {
  std::vector<std::string> seeds;
  // Mesh references become the sandbox's quad.obj (or demo.obj).
  const std::regex mesh(R"re("file"\s*:\s*"[^"]*\.obj")re");
  for (const fs::path& root : seedRoots())
    for (const fs::path& p : filesNamed(root, ".json")) {
      std::string text = readFile(p);
      const bool demo = p.parent_path().filename() == "demo";
      seeds.push_back(std::regex_replace(text, mesh, demo ? R"("file": "demo.obj")" : R"("file": "quad.obj")"));
    }
  return seeds;
}

std::vector<std::string> objSeeds() {
  std::vector<std::string> seeds;
  const std::regex mtllib(R"(mtllib[^\n]*)");
  for (const fs::path& root : seedRoots())
    for (const fs::path& p : filesNamed(root, ".obj")) {
      std::string text = readFile(p), mtl;
      std::smatch m;
      if (std::regex_search(text, m, mtllib)) {
        std::string name = m.str().substr(6);
        name.erase(0, name.find_first_not_of(" \t"));
        while (!name.empty() && (name.back() == '\r' || name.back() == ' ')) name.pop_back();
        std::error_code ec;
        if (fs::is_regular_file(p.parent_path() / name, ec)) mtl = readFile(p.parent_path() / name);
        text = std::regex_replace(text, mtllib, "mtllib fuzz.mtl");
      }
      seeds.push_back(mtl.empty() ? text : text + kMtlSeparator + mtl);
    }
  return seeds;
}

std::vector<std::string> filesSeeds(const std::vector<std::string>& extensions) {
  std::vector<std::string> seeds;
  for (const fs::path& root : seedRoots())
    for (const std::string& ext : extensions)
      for (const fs::path& p : filesNamed(root, ext)) seeds.push_back(readFile(p));
  return seeds;
}

std::vector<std::string> plySeeds() {
  using montecl_test::PlyEncoding;
  const montecl_test::MeshData tent = montecl_test::tentMesh();
  std::vector<std::string> seeds = {montecl_test::plyText(tent, PlyEncoding::Ascii, "s t"),
                                    montecl_test::plyText(tent, PlyEncoding::LittleEndian),
                                    montecl_test::plyText(tent, PlyEncoding::BigEndian, "texture_u texture_v"),
                                    "ply\nformat ascii 1.0\nelement vertex 4\nproperty double x\nproperty double y\n"
                                    "property double z\nproperty uchar red\nelement tristrips 1\n"
                                    "property list int int vertex_indices\nelement edge 1\nproperty int a\nend_header\n"
                                    "0 0 0 1\n1 0 0 2\n0 1 0 3\n1 1 0 4\n5 0 1 2 -1 3\n7\n"};
  for (const std::string& s : filesSeeds({".ply"})) seeds.push_back(s);
  return seeds;
}

std::vector<std::string> gltfSeeds() {
  const montecl_test::MeshData tent = montecl_test::tentMesh();
  std::string rich = montecl_test::gltfText(tent, 0.5f, "tent.bin");
  // Materials, textures, a camera and a node hierarchy, spliced into the tent's JSON.
  const std::string extra =
      R"("images":[{"uri":"wood.png"},{"uri":"data:image/png;base64,iVBORw0KGgo="}],"textures":[{"source":0},{"source":1,"sampler":0}],)"
      R"("samplers":[{"wrapS":33071}],"cameras":[{"type":"perspective","perspective":{"yfov":0.6,"aspectRatio":1.5,"znear":0.1}}],)"
      R"("extensionsUsed":["KHR_materials_emissive_strength","KHR_lights_punctual"],)";
  rich.insert(1, extra);
  const std::string material = R"("materials":[{)";
  rich.insert(rich.find(material) + material.size(),
              R"("alphaMode":"MASK","alphaCutoff":0.4,"emissiveFactor":[1,1,1],"extensions":{"KHR_materials_emissive_strength":{"emissiveStrength":3}},)"
              R"("normalTexture":{"index":1},)");
  const std::string nodes = R"("nodes":[)";
  rich.insert(rich.find(nodes) + nodes.size(), R"({"children":[1,2],"rotation":[0,0.7071068,0,0.7071068],"scale":[1,2,1]},)"
                                                R"({"camera":0,"translation":[0,1,5]},)");
  const std::string mesh = R"({"mesh":0,"translation":[0,0,0]})";
  rich.replace(rich.find(mesh), mesh.size(), R"({"mesh":0,"matrix":[-1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1]})");
  const std::string roots = R"("scenes":[{"nodes":[0]}])";
  (void)roots;
  // EXT_mesh_gpu_instancing: two instances (TRANSLATION, ROTATION, SCALE floats) in a second buffer.
  std::string instanced = montecl_test::gltfText(tent, 0.5f, "");
  {
    const float values[] = {0, 0, 0, 1, 0, -1, 0, 0, 0, 1, 0.6f, 0, 0, 0.8f, 1, 1, 1, 2, 0.5f, 1};
    std::string bytes(sizeof values, '\0');
    std::memcpy(&bytes[0], values, sizeof values);
    const std::string buffer = R"({"uri":"data:application/octet-stream;base64,)" + montecl_test::base64(bytes) +
                               R"(","byteLength":80})";
    const std::string buffers = R"("buffers":[)";
    instanced.insert(instanced.find(buffers) + buffers.size(), buffer + ",");  // buffer 0 now: the instances
    // The mesh's views move to buffer 1; the instance views and accessors come first.
    for (std::size_t p = 0; (p = instanced.find(R"("buffer":0)", p)) != std::string::npos; p += 10) instanced[p + 9] = '1';
    const std::string views = R"("bufferViews":[)";
    instanced.insert(instanced.find(views) + views.size(),
                     R"({"buffer":0,"byteOffset":0,"byteLength":24},{"buffer":0,"byteOffset":24,"byteLength":32},)"
                     R"({"buffer":0,"byteOffset":56,"byteLength":24},)");
    // Accessors 0-2 are the instances'; the mesh's accessors and views are renumbered by 3.
    std::string out;
    for (std::size_t p = 0; p < instanced.size();) {
      const std::size_t a = instanced.find_first_of("\"", p);
      if (a == std::string::npos) { out += instanced.substr(p); break; }
      out += instanced.substr(p, a - p);
      p = a;
      static const char* keys[] = {"\"bufferView\":", "\"POSITION\":", "\"NORMAL\":", "\"TEXCOORD_0\":", "\"indices\":"};
      bool done = false;
      for (const char* k : keys)
        if (instanced.compare(p, std::strlen(k), k) == 0) {
          std::size_t e = p + std::strlen(k), d = e;
          while (d < instanced.size() && std::isdigit(static_cast<unsigned char>(instanced[d]))) ++d;
          out += std::string(k) + std::to_string(std::stoi(instanced.substr(e, d - e)) + 3);
          p = d;
          done = true;
          break;
        }
      if (!done) out += instanced[p++];
    }
    instanced = out;
    const std::string accessors = R"("accessors":[)";
    instanced.insert(instanced.find(accessors) + accessors.size(),
                     R"({"bufferView":0,"componentType":5126,"count":2,"type":"VEC3"},)"
                     R"({"bufferView":1,"componentType":5126,"count":2,"type":"VEC4"},)"
                     R"({"bufferView":2,"componentType":5126,"count":2,"type":"VEC3"},)");
    const std::string node = R"({"mesh":0,"translation":[0,0,0]})";
    instanced.replace(instanced.find(node), node.size(),
                      R"({"mesh":0,"extensions":{"EXT_mesh_gpu_instancing":{"attributes":)"
                      R"({"TRANSLATION":0,"ROTATION":1,"SCALE":2}}}})");
  }
  // One mesh placed by three nodes (one mirrored): loaded once, rendered as three instances.
  std::string shared = montecl_test::gltfText(tent, 0.5f, "");
  {
    const std::string node = R"({"mesh":0,"translation":[0,0,0]})", roots = R"("scenes":[{"nodes":[0]}])";
    shared.replace(shared.find(node), node.size(),
                   R"({"mesh":0,"translation":[0,0,0]},{"mesh":0,"translation":[2,0,0]},{"mesh":0,"scale":[1,-1,1]})");
    shared.replace(shared.find(roots), roots.size(), R"("scenes":[{"nodes":[0,1,2]}])");
  }
  // TANGENT (VEC4 floats in a second buffer; w alternating) on that mesh: read, placed, mirrored.
  std::string tangents = shared;
  {
    std::string bytes;
    for (int v = 0; v < 6; ++v) {
      const float t[4] = {1, 0, 0, v % 2 ? -1.0f : 1.0f};
      bytes.append(reinterpret_cast<const char*>(t), sizeof t);
    }
    tangents.insert(tangents.find(R"(],"bufferViews")"), R"(,{"uri":"data:application/octet-stream;base64,)" +
                                                             montecl_test::base64(bytes) + R"(","byteLength":96})");
    tangents.insert(tangents.find(R"(],"accessors")"), R"(,{"buffer":1,"byteOffset":0,"byteLength":96})");
    tangents.insert(tangents.size() - 2, R"(,{"bufferView":4,"componentType":5126,"count":6,"type":"VEC4"})");
    tangents.replace(tangents.find(R"("POSITION":0)"), 12, R"("POSITION":0,"TANGENT":4)");
  }
  // KHR_draco_mesh_compression: the tent through the Draco encoder, exact (sequential) and
  // quantized (edgebreaker), so mutations reach the Draco decoder and the checks around it.
  std::vector<std::string> seeds = {montecl_test::gltfText(tent, 0.5f, ""), montecl_test::gltfText(tent, 0.25f, "tent.bin"),
                                    montecl_test::glbBytes(tent, 0.5f), rich, instanced, shared, tangents,
                                    montecl_test::gltfDracoText(tent, 0.5f, 0), montecl_test::gltfDracoText(tent, 0.5f, 11)};
  for (const std::string& s : filesSeeds({".gltf", ".glb"})) seeds.push_back(s);
  return seeds;
}

// Every directive the pbrt reader knows, over a few small scenes (and the .pbrt files in the tree).
// No sphere: each is 16k triangles, and mutations that repeat it only measure the tessellation.
std::vector<std::string> pbrtSeeds() {
  const std::string camera =
      "LookAt 0 1 5  0 1 0  0 1 0\nFilm \"rgb\" \"integer xresolution\" [ 8 ] \"integer yresolution\" [ 6 ]\n"
      "Camera \"perspective\" \"float fov\" [ 40 ] \"float lensradius\" 0.01 \"float focaldistance\" 5\n"
      "Sampler \"independent\" \"integer pixelsamples\" [ 4 ]\nIntegrator \"path\" \"integer maxdepth\" [ 3 ]\n"
      "PixelFilter \"box\"\n";
  std::vector<std::string> seeds = {
      camera + "WorldBegin\nAttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [ 4 4 4 ] \"bool twosided\" true\n"
               "Shape \"trianglemesh\" \"point3 P\" [ -1 0 0 1 0 0 1 2 0 -1 2 0 ] \"integer indices\" [ 0 1 2 0 2 3 ]"
               " \"normal N\" [ 0 0 1 0 0 1 0 0 1 0 0 1 ] \"point2 uv\" [ 0 0 1 0 1 1 0 1 ]\nAttributeEnd\n"
               "Shape \"disk\" \"float radius\" 0.5 \"float height\" 0.1\nReverseOrientation\nShape \"disk\" \"float innerradius\" 0.2\n",
      camera + "WorldBegin\nMakeNamedMaterial \"cu\" \"string type\" \"conductor\" \"spectrum eta\" \"metal-Cu-eta\""
               " \"spectrum k\" \"metal-Cu-k\" \"float uroughness\" 0.1 \"float vroughness\" 0.2\n"
               "Texture \"t\" \"spectrum\" \"checkerboard\" \"rgb tex1\" [ 1 0 0 ]\n"
               "Texture \"w\" \"spectrum\" \"imagemap\" \"string filename\" \"wood.png\" \"float uscale\" 2\n"
               "Material \"diffuse\" \"texture reflectance\" \"t\"\nNamedMaterial \"cu\"\n"
               "Transform [ 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1 ]\nShape \"plymesh\" \"string filename\" \"tent.ply\"\n"
               "Material \"dielectric\" \"spectrum eta\" \"glass-BK7\" \"float roughness\" 0.1\n"
               "Shape \"bilinearmesh\" \"point3 P\" [ 0 0 0 1 0 0 0 1 0 1 1 0 ]\n",
      camera + "WorldBegin\nLightSource \"point\" \"rgb I\" [ 1 1 1 ] \"point3 from\" [ 0 3 0 ]\n"
               "LightSource \"spot\" \"point3 from\" [ 0 3 0 ] \"point3 to\" [ 0 0 0 ] \"float coneangle\" 30\n"
               "LightSource \"distant\" \"blackbody L\" [ 5500 ]\nLightSource \"infinite\" \"rgb L\" [ .2 .2 .2 ]\n"
               "ObjectBegin \"o\"\nShape \"trianglemesh\" \"point3 P\" [ 0 0 0 1 0 0 0 1 0 ]\nObjectEnd\n"
               "TransformBegin\nTranslate 1 0 0\nRotate 30 0 1 0\nScale 2 2 2\nObjectInstance \"o\"\nTransformEnd\n"
               "CoordinateSystem \"c\"\nCoordSysTransform \"c\"\nConcatTransform [ 1 0 0 0 0 1 0 0 0 0 1 0 0 0 1 1 ]\n"
               "MakeNamedMedium \"m\" \"string type\" \"homogeneous\"\nMediumInterface \"m\" \"\"\n"
               "Include \"part.pbrt\"\n",
  };
  for (const std::string& s : filesSeeds({".pbrt"})) seeds.push_back(s);
  return seeds;
}

std::vector<std::string> exrSeeds() {
  using montecl::LayeredImage;
  std::vector<std::string> seeds;
  auto add = [&](int w, int h, const std::vector<std::string>& channels) {
    LayeredImage img;
    img.width = w;
    img.height = h;
    for (std::size_t c = 0; c < channels.size(); ++c) {
      std::vector<float> plane(img.pixelCount());
      for (std::size_t p = 0; p < plane.size(); ++p) plane[p] = channels[c] == "samples" ? 4.0f : 0.1f * float(p + c);
      img.set(channels[c], plane);
    }
    const fs::path p = fs::path(sandboxDir()) / "seed.exr";
    montecl::writeLayeredExr(p.string(), img);
    seeds.push_back(readFile(p));
    fs::remove(p);
  };
  add(4, 3, {"R", "G", "B", "samples", "var.R", "var.G", "var.B"});
  add(2, 2, {"R", "G", "B", "samples", "var.R", "var.G", "var.B", "albedo.R", "albedo.G", "albedo.B", "Z"});
  add(3, 1, {"R", "G", "B"});
  add(1, 1, {"R", "G", "B", "samples"});
  return seeds;
}

std::vector<std::string> cacheSeeds() {
  std::vector<std::string> seeds;
  auto add = [&](std::uint64_t check, const std::string& bin) {
    std::vector<unsigned char> b(bin.begin(), bin.end());
    std::vector<unsigned char> e = montecl::encodeCacheEntry(check, b);
    seeds.emplace_back(e.begin(), e.end());
  };
  add(kFuzzCacheCheck, std::string("\x7f" "ELF\x02\x01\x01\0\0\0\0\0\0\0\0\0", 16) + "program binary");
  add(kFuzzCacheCheck, "x");
  add(kFuzzCacheCheck ^ 1, "a binary under another key");
  seeds.push_back("MCLPRG01");
  seeds.push_back("");
  return seeds;
}

}  // namespace

const char* loaderName(Loader l) {
  switch (l) {
    case Loader::Scene: return "scene";
    case Loader::Obj: return "obj";
    case Loader::Exr: return "exr";
    case Loader::Cache: return "cache";
    case Loader::Ply: return "ply";
    case Loader::Gltf: return "gltf";
    case Loader::Pbrt: return "pbrt";
    case Loader::Mitsuba: return "mitsuba";
  }
  return "?";
}

const std::string& sandboxDir() {
  static Sandbox sandbox;
  return sandbox.dir;
}

Outcome fuzzScene(const std::uint8_t* data, std::size_t size) {
  const fs::path p = fs::path(sandboxDir()) / "scene.json";
  writeFile(p, reinterpret_cast<const char*>(data), size);
  return guarded([&] {
    std::vector<std::string> warnings;
    montecl::loadScene(p.string(), warnings);
    return true;
  });
}

Outcome fuzzObj(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const std::size_t sep = text.find(kMtlSeparator);
  const fs::path obj = fs::path(sandboxDir()) / "fuzz.obj", mtl = fs::path(sandboxDir()) / "fuzz.mtl";
  std::error_code ec;
  fs::remove(mtl, ec);
  if (sep == std::string::npos) {
    writeFile(obj, text);
  } else {
    writeFile(obj, text.substr(0, sep));
    writeFile(mtl, text.substr(sep + std::char_traits<char>::length(kMtlSeparator)));
  }
  return guarded([&] {
    montecl::Scene scene;
    std::vector<std::string> warnings;
    montecl::loadObjInto(obj.string(), scene, &warnings);
    return true;
  });
}

Outcome fuzzExr(const std::uint8_t* data, std::size_t size) {
  const fs::path p = fs::path(sandboxDir()) / "in.exr";
  writeFile(p, reinterpret_cast<const char*>(data), size);
  return guarded([&] {
    montecl::LayeredImage img = montecl::readLayeredImage(p.string());
    montecl::mergeLayeredImages({img, img}, {"a.exr", "b.exr"});
    return true;
  });
}

Outcome fuzzCache(const std::uint8_t* data, std::size_t size) {
  const fs::path p = fs::path(sandboxDir()) / "entry.bin";
  writeFile(p, reinterpret_cast<const char*>(data), size);
  return guarded([&] {
    std::vector<unsigned char> bin;
    return montecl::readCacheEntryFile(p.string(), kFuzzCacheCheck, bin);
  });
}

Outcome fuzzPly(const std::uint8_t* data, std::size_t size) {
  const fs::path p = fs::path(sandboxDir()) / "fuzz.ply";
  writeFile(p, reinterpret_cast<const char*>(data), size);
  return guarded([&] {
    montecl::Scene scene;
    std::vector<std::string> warnings;
    montecl::loadPlyInto(p.string(), scene, &warnings);
    return true;
  });
}

Outcome fuzzGltf(const std::uint8_t* data, std::size_t size) {
  const bool glb = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
  const fs::path p = fs::path(sandboxDir()) / (glb ? "fuzz.glb" : "fuzz.gltf");
  writeFile(p, reinterpret_cast<const char*>(data), size);
  return guarded([&] {
    montecl::Scene scene;
    std::vector<std::string> warnings;
    montecl::Camera camera;
    montecl::loadGltfInto(p.string(), scene, &warnings, &camera);
    return true;
  });
}

Outcome fuzzPbrt(const std::uint8_t* data, std::size_t size) {
  const fs::path p = fs::path(sandboxDir()) / "fuzz.pbrt";
  writeFile(p, reinterpret_cast<const char*>(data), size);
  return guarded([&] {
    std::vector<std::string> warnings;
    montecl::loadScene(p.string(), warnings);
    return true;
  });
}

Outcome runEntry(Loader l, const std::uint8_t* data, std::size_t size) {
  switch (l) {
    case Loader::Scene: return fuzzScene(data, size);
    case Loader::Obj: return fuzzObj(data, size);
    case Loader::Exr: return fuzzExr(data, size);
    case Loader::Cache: return fuzzCache(data, size);
    case Loader::Ply: return fuzzPly(data, size);
    case Loader::Gltf: return fuzzGltf(data, size);
    case Loader::Pbrt: return fuzzPbrt(data, size);
    case Loader::Mitsuba: return fuzzMitsuba(data, size);
  }
  throw std::logic_error("unknown loader");
}

std::vector<std::string> seedInputs(Loader l) {
  switch (l) {
    case Loader::Scene: return sceneSeeds();
    case Loader::Obj: return objSeeds();
    case Loader::Exr: return exrSeeds();
    case Loader::Cache: return cacheSeeds();
    case Loader::Ply: return plySeeds();
    case Loader::Gltf: return gltfSeeds();
    case Loader::Pbrt: return pbrtSeeds();
    case Loader::Mitsuba: return mitsubaSeeds();
  }
  return {};
}

}  // namespace montecl_fuzz
