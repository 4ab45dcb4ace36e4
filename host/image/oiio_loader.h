// oiio_loader.h: image input/output through OpenImageIO, loaded on first use (dlopen of
// libmontecl_oiio.so, see oiio_plugin_abi.h). The module is looked for in $MONTECL_IMAGE_PLUGIN
// (a file), beside the running executable, then in <executable>/../lib/montecl/.
#pragma once
#include <functional>
#include <string>
#include <vector>

namespace montecl {

struct LayeredImage;

// Writes image to exactly path (not atomic: callers wrap it in writeAtomically). Throws
// RuntimeError "cannot write <displayPath>: <reason>" on failure or when the module is missing.
void oiioWrite(const std::string& path, const std::string& displayPath, const LayeredImage& image);

// Says, from the size a file declares (width, height, channels), why it must not be decoded, or
// "" to decode it. Asked after the header is read, before any pixel is.
using ImageSizeCheck = std::function<std::string(int width, int height, int channels)>;

// Reads every channel of path. Throws InputError "<path>: cannot read image: <reason>" (the
// reason check gave when it refused the declared size).
LayeredImage oiioRead(const std::string& path, const ImageSizeCheck& check = {});

// The same for an encoded image held in memory: name (its extension picks the format) is what
// errors call it. Throws InputError "<name>: cannot read image: <reason>".
LayeredImage oiioReadMemory(const std::string& name, const std::vector<unsigned char>& bytes,
                            const ImageSizeCheck& check = {});

}  // namespace montecl
