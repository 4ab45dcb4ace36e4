// mpi.cpp: job/mpi.h: the launch rule, and the dlopened MPI module.
#include "job/mpi.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <mutex>

#include "job/mpi_plugin_abi.h"
#include "util/errors.h"

namespace montecl::jobs {
namespace {

constexpr const char* kModuleName = "libmontecl_mpi.so";
const MonteclMpiApi* gApi = nullptr;

bool envSet(const char* name) {
  const char* v = std::getenv(name);
  return v && *v;
}

const MonteclMpiApi* loadModule() {
  std::vector<std::filesystem::path> paths;
  if (const char* env = std::getenv("MONTECL_MPI_PLUGIN"); env && *env) {
    paths.push_back(env);
  } else {
    std::error_code ec;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (!ec) paths = {exe.parent_path() / kModuleName, exe.parent_path() / ".." / "lib" / "montecl" / kModuleName};
  }
  std::string tried;
  for (const std::filesystem::path& path : paths) {
    if (!std::filesystem::exists(path)) {
      tried += (tried.empty() ? "" : ", ") + path.string();
      continue;
    }
    // RTLD_GLOBAL: Open MPI dlopens its own components, which need libmpi's symbols.
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_GLOBAL);
    if (!handle) throw RuntimeError("launched by MPI but cannot load " + path.string() + ": " + dlerror());
    auto api = reinterpret_cast<MonteclMpiApiFn>(dlsym(handle, MONTECL_MPI_API_SYMBOL));
    if (!api) throw RuntimeError(path.string() + " lacks " + MONTECL_MPI_API_SYMBOL);
    return api();
  }
  throw RuntimeError(std::string("launched by MPI but ") + kModuleName + " was not found (tried " + tried +
                     "; build with MPI installed, set MONTECL_MPI_PLUGIN, or MONTECL_MPI=0 to run alone)");
}

}  // namespace

bool launchedByMpi() {
  if (const char* force = std::getenv("MONTECL_MPI"); force && *force) return std::string(force) != "0";
  if (envSet("OMPI_COMM_WORLD_SIZE") || envSet("PMI_SIZE") || envSet("PMIX_RANK")) return true;
  const char* tasks = std::getenv("SLURM_NTASKS");
  return envSet("SLURM_PROCID") && tasks && std::atoi(tasks) > 1;
}

const World& world() {
  static World w;
  static std::once_flag once;
  std::call_once(once, [] {
    if (!launchedByMpi()) return;
    gApi = loadModule();
    char err[512] = {0};
    if (gApi->init(&w.rank, &w.size, &w.localRank, err, sizeof err) != 0)
      throw RuntimeError(std::string("cannot join the MPI job: ") + err);
    w.active = true;
    std::atexit([] { gApi->finalize(); });
  });
  return w;
}

void allreduceSum(std::vector<std::uint64_t>& values) {
  if (!world().active) return;
  if (gApi->allreduceSum(values.data(), int(values.size())) != 0) throw RuntimeError("MPI_Iallreduce failed");
}

void gatherBytes(const std::string& send, std::string& recv, const std::vector<int>& sizes,
                 const std::vector<int>& offsets) {
  if (!world().active) {
    recv = send;
    return;
  }
  if (gApi->gatherBytes(send.data(), int(send.size()), recv.data(), sizes.data(), offsets.data()) != 0)
    throw RuntimeError("MPI_Igatherv failed");
}

int failed(int code) {
  if (!launchedByMpi()) return code;
  try {
    world();  // a rank that fails before joining joins now, so that its abort ends the whole job
  } catch (const std::exception&) {
    return code;
  }
  if (gApi && world().active) {
    std::cerr.flush();
    gApi->abortAll(code);
  }
  return code;
}

}  // namespace montecl::jobs
