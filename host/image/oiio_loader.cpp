// oiio_loader.cpp: finds and dlopens libmontecl_oiio.so once, and forwards image reads and writes.
#include "image/oiio_loader.h"

#include <dlfcn.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <vector>

#include "image/exr_layers.h"
#include "image/oiio_plugin_abi.h"
#include "util/errors.h"

namespace montecl {
namespace {

constexpr const char* kModuleName = "libmontecl_oiio.so";

struct Module {
  MonteclOiioWriteFn write = nullptr;
  MonteclOiioReadFn read = nullptr;
  MonteclOiioReadMemoryFn readMemory = nullptr;
  std::string error;  // why the module could not be used (empty when it loaded)
};

std::vector<std::filesystem::path> candidatePaths() {
  if (const char* env = std::getenv("MONTECL_IMAGE_PLUGIN"); env && *env) return {env};
  std::error_code ec;
  std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) return {kModuleName};  // the dynamic loader's own search path
  std::filesystem::path dir = exe.parent_path();
  return {dir / kModuleName, dir / ".." / "lib" / "montecl" / kModuleName};
}

Module loadModule() {
  Module m;
  std::string tried;
  for (const std::filesystem::path& path : candidatePaths()) {
    if (path.has_parent_path() && !std::filesystem::exists(path)) {
      tried += (tried.empty() ? "" : ", ") + path.string();
      continue;
    }
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
      m.error = "cannot load the OpenImageIO module: " + std::string(dlerror());
      return m;
    }
    m.write = reinterpret_cast<MonteclOiioWriteFn>(dlsym(handle, MONTECL_OIIO_WRITE_SYMBOL));
    m.read = reinterpret_cast<MonteclOiioReadFn>(dlsym(handle, MONTECL_OIIO_READ_SYMBOL));
    m.readMemory = reinterpret_cast<MonteclOiioReadMemoryFn>(dlsym(handle, MONTECL_OIIO_READ_MEMORY_SYMBOL));
    if (!m.write || !m.read || !m.readMemory) m.error = path.string() + " lacks the montecl_oiio_* entry points";
    return m;  // never dlclosed: OpenImageIO keeps threads and caches until exit
  }
  m.error = std::string("the OpenImageIO module ") + kModuleName + " was not found (tried " + tried +
            "; set MONTECL_IMAGE_PLUGIN to its path)";
  return m;
}

const Module& module() {
  static std::once_flag once;
  static Module m;
  std::call_once(once, [] { m = loadModule(); });
  return m;
}

}  // namespace

void oiioWrite(const std::string& path, const std::string& displayPath, const LayeredImage& image) {
  const Module& m = module();
  if (!m.error.empty()) throw RuntimeError("cannot write " + displayPath + ": " + m.error);
  char err[1024] = {0};
  if (m.write(path.c_str(), &image, err, sizeof err) != 0)
    throw RuntimeError("cannot write " + displayPath + ": " + err);
}

namespace {

// The C callback of the plugin's size check: forwards to check; its reason comes back through err.
int forwardSizeCheck(void* context, int w, int h, int c, char* e, std::size_t n) {
  const std::string why = (*static_cast<const ImageSizeCheck*>(context))(w, h, c);
  if (why.empty()) return 0;
  std::snprintf(e, n, "%s", why.c_str());
  return 1;
}

}  // namespace

LayeredImage oiioRead(const std::string& path, const ImageSizeCheck& check) {
  const Module& m = module();
  if (!m.error.empty()) throw RuntimeError("cannot read " + path + ": " + m.error);
  LayeredImage image;
  char err[1024] = {0};
  if (m.read(path.c_str(), &image, check ? forwardSizeCheck : nullptr, const_cast<ImageSizeCheck*>(&check), err,
             sizeof err) != 0) throwInputError(path, "", std::string("cannot read image: ") + err);
  return image;
}

LayeredImage oiioReadMemory(const std::string& name, const std::vector<unsigned char>& bytes,
                            const ImageSizeCheck& check) {
  const Module& m = module();
  if (!m.error.empty()) throw RuntimeError("cannot read " + name + ": " + m.error);
  LayeredImage image;
  char err[1024] = {0};
  if (m.readMemory(name.c_str(), bytes.data(), bytes.size(), &image, check ? forwardSizeCheck : nullptr,
                   const_cast<ImageSizeCheck*>(&check), err, sizeof err) != 0)
    throwInputError(name, "", std::string("cannot read image: ") + err);
  return image;
}

}  // namespace montecl
