// fuzz_seeds.cpp: writes the seed corpus of every loader, <out>/<loader>/seed-NNN
// (fuzz_entries.h seedInputs(): scenes/test/good, scenes/test/bad, scenes/demo, small EXRs).
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "fuzz_entries.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: fuzz_seeds <out-folder>\n");
    return 2;
  }
  namespace fs = std::filesystem;
  for (montecl_fuzz::Loader l : montecl_fuzz::kLoaders) {
    const fs::path dir = fs::path(argv[1]) / montecl_fuzz::loaderName(l);
    fs::create_directories(dir);
    const auto seeds = montecl_fuzz::seedInputs(l);
    for (std::size_t i = 0; i < seeds.size(); ++i) {
      char name[32];
      std::snprintf(name, sizeof name, "seed-%03zu", i);
      std::ofstream(dir / name, std::ios::binary) << seeds[i];
    }
    std::printf("%s: %zu seeds in %s\n", montecl_fuzz::loaderName(l), seeds.size(), dir.c_str());
  }
  return 0;
}
