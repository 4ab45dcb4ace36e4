// fuzz_target.cpp: the libFuzzer harness of one loader, compiled once per loader with
// -DMONTECL_FUZZ_LOADER=Scene|Obj|Exr|Cache|Ply|Gltf (fuzz_scene, fuzz_obj, fuzz_exr, fuzz_cache,
// fuzz_ply, fuzz_gltf).
// An input that ends in anything but Loaded/Rejected (another exception, a crash, a sanitizer
// report, a timeout) is a finding. See docs/fuzzing.md.
#include <cstddef>
#include <cstdint>

#include "fuzz_entries.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  montecl_fuzz::runEntry(montecl_fuzz::Loader::MONTECL_FUZZ_LOADER, data, size);
  return 0;
}
