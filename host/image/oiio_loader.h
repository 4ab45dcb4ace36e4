// oiio_loader.h: image input/output through OpenImageIO, loaded on first use (dlopen of
// libmontecl_oiio.so, see oiio_plugin_abi.h). The module is looked for in $MONTECL_IMAGE_PLUGIN
// (a file), beside the running executable, then in <executable>/../lib/montecl/.
#pragma once
#include <string>
#include <vector>

namespace montecl {

struct LayeredImage;

// Writes image to exactly path (not atomic: callers wrap it in writeAtomically). Throws
// RuntimeError "cannot write <displayPath>: <reason>" on failure or when the module is missing.
void oiioWrite(const std::string& path, const std::string& displayPath, const LayeredImage& image);

// Reads every channel of path. Throws InputError "<path>: cannot read image: <reason>".
LayeredImage oiioRead(const std::string& path);

// The same for an encoded image held in memory: name (its extension picks the format) is what
// errors call it. Throws InputError "<name>: cannot read image: <reason>".
LayeredImage oiioReadMemory(const std::string& name, const std::vector<unsigned char>& bytes);

}  // namespace montecl
