// fuzz_entries.h: one fuzz entry point per input loader of montecl, shared by the libFuzzer
// harnesses (fuzz/fuzz_*.cpp, cmake -DMONTECL_FUZZ=ON) and the seeded mutation loop of the test
// suite (tests/test_fuzz.cpp).
//
// Each entry takes the bytes of one input, writes them to files in a private temporary folder as
// the loader needs, and runs the loader. It returns Loaded, or Rejected when the loader refused
// the input the way montecl reports bad input (InputError, RuntimeError, or a cache entry that
// does not verify). Any other exception propagates: to the caller that is a finding, as is a
// crash, a sanitizer report or a hang.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace montecl_fuzz {

enum class Outcome { Loaded, Rejected };

enum class Loader { Scene, Obj, Exr, Cache, Ply, Gltf, Pbrt, Mitsuba };
constexpr Loader kLoaders[] = {Loader::Scene, Loader::Obj,  Loader::Exr,  Loader::Cache,
                               Loader::Ply,   Loader::Gltf, Loader::Pbrt, Loader::Mitsuba};
const char* loaderName(Loader l);  // "scene", "obj", "exr", "cache", "ply", "gltf", "pbrt", "mitsuba"

// Scene JSON: the bytes are <sandbox>/scene.json, loaded by loadScene(). The sandbox folder also
// holds quad.obj/quad.mtl (scenes/test/good) and demo.obj/demo.mtl (scenes/demo), so that mesh
// references of the seeds resolve.
Outcome fuzzScene(const std::uint8_t* data, std::size_t size);

// OBJ + MTL: the bytes up to the first line "#--mtl--" are <sandbox>/fuzz.obj, the rest (if any)
// <sandbox>/fuzz.mtl (the seeds say `mtllib fuzz.mtl`); loaded by loadObjInto().
Outcome fuzzObj(const std::uint8_t* data, std::size_t size);
extern const char* const kMtlSeparator;  // "\n#--mtl--\n"

// EXR input of `montecl merge`: the bytes are <sandbox>/in.exr, read by readLayeredImage() (the
// OpenImageIO module) and, when that succeeds, merged with itself by mergeLayeredImages().
Outcome fuzzExr(const std::uint8_t* data, std::size_t size);

// Program-cache entry: the bytes are <sandbox>/entry.bin, read and verified by
// readCacheEntryFile() against kFuzzCacheCheck.
Outcome fuzzCache(const std::uint8_t* data, std::size_t size);
constexpr std::uint64_t kFuzzCacheCheck = 0x0123456789abcdefull;

// PLY: the bytes are <sandbox>/fuzz.ply, loaded by loadPlyInto().
Outcome fuzzPly(const std::uint8_t* data, std::size_t size);

// glTF: the bytes are <sandbox>/fuzz.glb when they start with "glTF", else <sandbox>/fuzz.gltf;
// loaded by loadGltfInto(). The sandbox also holds tent.bin (the external buffer of a seed) and
// wood.png (a texture the seeds name).
Outcome fuzzGltf(const std::uint8_t* data, std::size_t size);

// pbrt-v4: the bytes are <sandbox>/fuzz.pbrt, loaded by loadScene(). The sandbox also holds
// tent.ply (a plymesh the seeds name) and part.pbrt (an Include).
Outcome fuzzPbrt(const std::uint8_t* data, std::size_t size);

// Mitsuba 3 XML (fuzz/fuzz_mitsuba.cpp): the bytes are <sandbox>/fuzz.xml, loaded by loadScene().
// The sandbox also holds tent.ply and part.xml (an <include>); the seeds go through every tag family.
Outcome fuzzMitsuba(const std::uint8_t* data, std::size_t size);
std::vector<std::string> mitsubaSeeds();

Outcome runEntry(Loader l, const std::uint8_t* data, std::size_t size);

// Seed inputs of a loader, from the source tree (scenes/test/good, scenes/test/bad, scenes/demo);
// the EXR seeds are written here through the OpenImageIO module (small AOV images), the PLY and
// glTF seeds also by tests/fixtures/mesh_files.h (the tent model in every encoding).
std::vector<std::string> seedInputs(Loader l);

// The private temporary folder of this process (created on first use, removed at exit).
const std::string& sandboxDir();

}  // namespace montecl_fuzz
