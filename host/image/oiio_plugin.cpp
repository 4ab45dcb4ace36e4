// oiio_plugin.cpp: libmontecl_oiio.so, montecl's only user of OpenImageIO (see oiio_plugin_abi.h).
// Reads: a path and montecl::LayeredImage planes. Writes: the image file (to exactly the path it is
// given; the caller makes the write atomic), or the planes read back. Never throws.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <fcntl.h>
#include <unistd.h>

#include <cstdio>
#include <exception>
#include <mutex>
#include <string>
#include <type_traits>
#include <vector>

#include "image/exr_layers.h"
#include "image/image_limits.h"
#include "image/oiio_plugin_abi.h"

namespace {

int fail(char* err, std::size_t errSize, std::string message) {
  for (char& c : message)
    if (c == '\n' || c == '\r') c = ' ';
  while (!message.empty() && message.back() == ' ') message.pop_back();
  if (errSize > 0) std::snprintf(err, errSize, "%s", message.c_str());
  return 1;
}

int writeImage(const char* path, const montecl::LayeredImage& image, char* err, std::size_t errSize) {
  using namespace OIIO;
  const std::size_t count = image.pixelCount(), nch = image.channels.size();
  std::vector<float> pixels(count * nch);
  for (std::size_t p = 0; p < count; ++p)
    for (std::size_t c = 0; c < nch; ++c) pixels[p * nch + c] = image.planes[c][p];
  ImageSpec spec(image.width, image.height, int(nch), TypeDesc::FLOAT);
  spec.channelnames = image.channels;
  spec.alpha_channel = -1;
  spec.z_channel = -1;
  for (std::size_t c = 0; c < nch; ++c)
    if (image.channels[c] == "Z") spec.z_channel = int(c);
  spec.attribute("compression", "zip");
  for (const auto& [name, value] : image.attributes) spec.attribute(name, value);
  auto out = ImageOutput::create(path);
  if (!out) return fail(err, errSize, OIIO::geterror());
  if (!out->open(path, spec) || !out->write_image(TypeDesc::FLOAT, pixels.data()) || !out->close())
    return fail(err, errSize, out->geterror());
  return 0;
}

// libpng prints its errors to stderr itself ("libpng error: IDAT: ...") before OpenImageIO
// reports the same error to us: a bad image would be two lines. While any read runs, stderr goes to
// /dev/null; reads run in parallel (textures), so the first in redirects and the last out restores.
class QuietStderr {
 public:
  QuietStderr() {
    std::lock_guard<std::mutex> lock(mutex());
    if (depth()++ > 0) return;
    std::fflush(stderr);
    saved() = ::dup(2);
    const int null = ::open("/dev/null", O_WRONLY);
    if (saved() >= 0 && null >= 0) ::dup2(null, 2);
    if (null >= 0) ::close(null);
  }
  ~QuietStderr() {
    std::lock_guard<std::mutex> lock(mutex());
    if (--depth() > 0) return;
    std::fflush(stderr);
    if (saved() >= 0) {
      ::dup2(saved(), 2);
      ::close(saved());
    }
    saved() = -1;
  }
  QuietStderr(const QuietStderr&) = delete;
  QuietStderr& operator=(const QuietStderr&) = delete;

 private:
  static std::mutex& mutex() {
    static std::mutex m;
    return m;
  }
  static int& depth() {
    static int d = 0;
    return d;
  }
  static int& saved() {
    static int fd = -1;
    return fd;
  }
};

// proxy: the encoded bytes when the image is held in memory (path then only names its format).
int readImage(const char* path, OIIO::Filesystem::IOProxy* proxy, montecl::LayeredImage& image,
              MonteclOiioSizeCheckFn check, void* checkContext, char* err, std::size_t errSize) {
  using namespace OIIO;
  const QuietStderr quiet;
  ImageSpec opened, config;
  // Colour as stored: OpenImageIO would premultiply a PNG's or TGA's unassociated alpha into it.
  config.attribute("oiio:UnassociatedAlpha", 1);
  // The reader the file name's extension selects, opened directly: ImageInput::open() would try
  // every other format reader of OpenImageIO in turn on a file its own reader refuses (~10 ms).
  auto in = ImageInput::create(path, false, &config, proxy);
  if (!in) return fail(err, errSize, OIIO::geterror());
  if (proxy && !in->set_ioproxy(proxy)) return fail(err, errSize, "this image format cannot be read from memory");
  if (!in->open(path, opened, config)) return fail(err, errSize, in->geterror());
  const ImageSpec& spec = in->spec();
  if (spec.deep) return fail(err, errSize, "deep images are not supported");
  if (const std::string why = montecl::imageSizeProblem(spec.width, spec.height, spec.nchannels, spec.x, spec.y);
      !why.empty())
    return fail(err, errSize, why);
  if (check && check(checkContext, spec.width, spec.height, spec.nchannels, err, errSize) != 0) return 1;
  image.width = spec.width;
  image.height = spec.height;
  const std::size_t count = image.pixelCount(), nch = std::size_t(spec.nchannels);
  std::vector<float> pixels(count * nch);
  if (!in->read_image(0, 0, 0, int(nch), TypeDesc::FLOAT, pixels.data())) return fail(err, errSize, in->geterror());
  in->close();
  image.channels.clear();
  image.planes.clear();
  image.attributes.clear();
  image.pixelType = spec.format.c_str();
  for (const ParamValue& p : spec.extra_attribs)
    if (p.type() == TypeDesc::STRING && p.name().string().rfind("montecl:", 0) == 0)
      image.attributes[p.name().string()] = p.get_string();
  for (std::size_t c = 0; c < nch; ++c) {
    std::vector<float> plane(count);
    for (std::size_t p = 0; p < count; ++p) plane[p] = pixels[p * nch + c];
    image.channels.push_back(c < spec.channelnames.size() ? spec.channelnames[c] : "channel" + std::to_string(c));
    image.planes.push_back(std::move(plane));
  }
  return 0;
}

}  // namespace

extern "C" {

__attribute__((visibility("default"))) int montecl_oiio_write(const char* path, const montecl::LayeredImage* image,
                                                              char* err, std::size_t errSize) {
  try {
    return writeImage(path, *image, err, errSize);
  } catch (const std::exception& e) {
    return fail(err, errSize, e.what());
  }
}

__attribute__((visibility("default"))) int montecl_oiio_read(const char* path, montecl::LayeredImage* image,
                                                             MonteclOiioSizeCheckFn check, void* checkContext,
                                                             char* err, std::size_t errSize) {
  try {
    return readImage(path, nullptr, *image, check, checkContext, err, errSize);
  } catch (const std::exception& e) {
    return fail(err, errSize, e.what());
  }
}

__attribute__((visibility("default"))) int montecl_oiio_read_memory(const char* name, const unsigned char* data,
                                                                    std::size_t size, montecl::LayeredImage* image,
                                                                    MonteclOiioSizeCheckFn check, void* checkContext,
                                                                    char* err, std::size_t errSize) {
  try {
    OIIO::Filesystem::IOMemReader proxy(data, size);
    return readImage(name, &proxy, *image, check, checkContext, err, errSize);
  } catch (const std::exception& e) {
    return fail(err, errSize, e.what());
  }
}

}  // extern "C"

// Both entry points must match the types the loader casts them to.
static_assert(std::is_same<decltype(&montecl_oiio_write), MonteclOiioWriteFn>::value, "plugin ABI");
static_assert(std::is_same<decltype(&montecl_oiio_read), MonteclOiioReadFn>::value, "plugin ABI");
static_assert(std::is_same<decltype(&montecl_oiio_read_memory), MonteclOiioReadMemoryFn>::value, "plugin ABI");
