// oidn_denoiser.cpp: loads Open Image Denoise with dlopen and runs its "RT" filter (see
// oidn_denoiser.h). Reads the library file; writes nothing.
#include "image/oidn_denoiser.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <initializer_list>
#include <utility>

#include "image/oidn_api.h"
#include "util/errors.h"

namespace montecl {
namespace {

namespace fs = std::filesystem;

const char* const kSetup = "bash scripts/setup.sh --oidn";

// The wheel puts the library under <venv>/lib/pythonX.Y/site-packages/pyoidn/oidn/lib; the Python
// version is whatever the venv was made with, so the lib folder is searched.
std::string findInVenv(const fs::path& venv) {
  std::error_code ec;
  for (const fs::directory_entry& py : fs::directory_iterator(venv / "lib", ec)) {
    const fs::path lib = py.path() / "site-packages" / "pyoidn" / "oidn" / "lib" / "libOpenImageDenoise.so.2";
    if (fs::exists(lib, ec)) return lib.string();
  }
  return "";
}

struct Loaded {
  oidn::Api api;
  oidn::Device device = nullptr;  // created and committed once: the filter runs on it
  std::string problem;            // "" when api is complete and the device works
};

template <class Fn>
bool bind(void* handle, const char* name, Fn& fn, std::string& problem) {
  fn = reinterpret_cast<Fn>(dlsym(handle, name));
  if (!fn && problem.empty()) problem = std::string("has no symbol ") + name + " (not Open Image Denoise 2.x?)";
  return fn != nullptr;
}

Loaded load() {
  Loaded l;
  const char* env = std::getenv("MONTECL_OIDN_LIBRARY");
  const std::string path = oidnLibraryPath();
  const std::string fix = ": install it with `" + std::string(kSetup) + "` (or set MONTECL_OIDN_LIBRARY)";
  if (path.empty() || !fs::exists(path)) {
    l.problem = "--denoise needs Open Image Denoise, not found (" +
                (env && *env ? "MONTECL_OIDN_LIBRARY=" + path : std::string("no libOpenImageDenoise.so.2 in the oidn venv")) +
                ")" + fix;
    return l;
  }
  // dlopen of a FIFO blocks until a writer comes (forever), of a folder or device fails obscurely:
  // regular files only, as for --resume.
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) {
    l.problem = "--denoise: " + path + " is not a regular file" + fix;
    return l;
  }
  // The handle stays open for the process: the filter may run more than once.
  void* h = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!h) {
    const char* why = dlerror();
    l.problem = "--denoise: cannot load " + path + " (" + (why ? why : "dlopen failed") + ")" + fix;
    return l;
  }
  std::string bad;
  oidn::Api& a = l.api;
  bind(h, "oidnNewDevice", a.newDevice, bad);
  bind(h, "oidnCommitDevice", a.commitDevice, bad);
  bind(h, "oidnReleaseDevice", a.releaseDevice, bad);
  bind(h, "oidnGetDeviceError", a.getDeviceError, bad);
  bind(h, "oidnNewFilter", a.newFilter, bad);
  bind(h, "oidnSetSharedFilterImage", a.setSharedFilterImage, bad);
  bind(h, "oidnSetFilterBool", a.setFilterBool, bad);
  bind(h, "oidnSetFilterInt", a.setFilterInt, bad);
  bind(h, "oidnCommitFilter", a.commitFilter, bad);
  bind(h, "oidnExecuteFilter", a.executeFilter, bad);
  bind(h, "oidnReleaseFilter", a.releaseFilter, bad);
  if (!bad.empty()) {
    l.problem = "--denoise: " + path + " " + bad + fix;
    return l;
  }
  // The CPU device is created and committed now, before any work: a core library without its
  // device module loads and exports every symbol, and only fails here.
  std::string error;
  l.device = a.newDevice(oidn::kDeviceTypeCpu);
  const char* msg = nullptr;
  if (a.getDeviceError(l.device, &msg) != oidn::kErrorNone || !l.device) {
    error = msg && *msg ? msg : "no CPU device";
  } else {
    a.commitDevice(l.device);
    if (a.getDeviceError(l.device, &msg) != oidn::kErrorNone) error = msg && *msg ? msg : "unknown error";
  }
  if (!error.empty()) {
    if (l.device) a.releaseDevice(l.device);
    l.device = nullptr;
    l.problem = "--denoise: " + path + " cannot create its CPU device (" + error + ")" + fix;
  }
  return l;
}

const Loaded& loaded() {
  static const Loaded l = load();
  return l;
}

}  // namespace

std::string oidnLibraryPath() {
  if (const char* env = std::getenv("MONTECL_OIDN_LIBRARY"); env && *env) return env;
  fs::path venv;
  if (const char* v = std::getenv("MONTECL_OIDN_VENV"); v && *v)
    venv = v;
  else if (const char* home = std::getenv("HOME"); home && *home)
    venv = fs::path(home) / ".cache" / "montecl" / "oidn-venv";
  return venv.empty() ? "" : findInVenv(venv);
}

std::string oidnProblem() { return loaded().problem; }

std::vector<float> oidnDenoise(int width, int height, const std::vector<float>& color,
                               const std::vector<float>& albedo, const std::vector<float>& normal,
                               int quality) {
  const Loaded& l = loaded();
  if (!l.problem.empty()) throw RuntimeError(l.problem);
  const oidn::Api& a = l.api;
  const std::size_t w = std::size_t(width), h = std::size_t(height);
  std::vector<float> out(3 * w * h, 0.0f);
  // The filter reads the inputs in place; it never writes them (the API takes void*).
  std::vector<float> in = color, alb = albedo, nrm = normal;
  oidn::Device dev = l.device;
  std::string error;
  auto check = [&]() {
    const char* msg = nullptr;
    if (error.empty() && a.getDeviceError(dev, &msg) != oidn::kErrorNone)
      error = msg && *msg ? msg : "unknown error";
  };
  // One RT filter over the shared images `images` (name, buffer) into `output`.
  auto run = [&](std::initializer_list<std::pair<const char*, float*>> images, float* output, bool hdr, bool cleanAux,
                 int q) {
    if (!error.empty()) return;
    oidn::Filter f = a.newFilter(dev, "RT");
    check();
    if (!f) {
      if (error.empty()) error = "no RT filter";
      return;
    }
    for (const auto& [name, data] : images) a.setSharedFilterImage(f, name, data, oidn::kFormatFloat3, w, h, 0, 0, 0);
    a.setSharedFilterImage(f, "output", output, oidn::kFormatFloat3, w, h, 0, 0, 0);
    if (hdr) a.setFilterBool(f, "hdr", true);  // radiance, not display values
    if (cleanAux) a.setFilterBool(f, "cleanAux", true);
    a.setFilterInt(f, "quality", q);
    a.commitFilter(f);
    check();
    if (error.empty()) a.executeFilter(f);
    check();
    a.releaseFilter(f);
  };
  // The guides are first-hit averages over each pixel's own samples, as noisy as the colour at low
  // sample counts: each is denoised on its own first (OIDN's prefiltering), and the colour's filter
  // is then told they are clean (cleanAux), so it keeps the detail they show instead of hedging.
  std::vector<float> albClean(alb.size()), nrmClean(nrm.size());
  // The guides' own filters at OIDN's fast quality: on the Cornell box (128², 16 spp, 5 seeds) the
  // result's relMSE is the same as with high-quality prefilters, at a third of their time.
  const int auxQuality = oidn::kQualityFast;
  run({{"albedo", alb.data()}}, albClean.data(), false, false, auxQuality);
  run({{"normal", nrm.data()}}, nrmClean.data(), false, false, auxQuality);
  run({{"color", in.data()}, {"albedo", albClean.data()}, {"normal", nrmClean.data()}}, out.data(), true, true, quality);
  if (!error.empty()) throw RuntimeError("Open Image Denoise: " + error);
  return out;
}

}  // namespace montecl
