// exr_writer.cpp: LayeredImage -> OpenEXR file (scanlines, ZIP, float channels, string attributes),
// compressed on every core.
#include "image/exr_writer.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>
#include <ImfThreading.h>

#include <algorithm>
#include <exception>
#include <thread>

#include "image/exr_layers.h"
#include "util/errors.h"

namespace montecl {

void writeExrFile(const std::string& path, const std::string& displayPath, const LayeredImage& image) {
  try {
    Imf::Header header(image.width, image.height);
    header.compression() = Imf::ZIP_COMPRESSION;
    for (const std::string& name : image.channels) header.channels().insert(name, Imf::Channel(Imf::FLOAT));
    for (const auto& [name, value] : image.attributes) header.insert(name, Imf::StringAttribute(value));
    // Planar storage: one Slice per plane, x stride one float, y stride one row.
    Imf::FrameBuffer frame;
    const std::size_t rowBytes = sizeof(float) * std::size_t(image.width);
    for (std::size_t c = 0; c < image.channels.size(); ++c)
      frame.insert(image.channels[c], Imf::Slice(Imf::FLOAT, (char*)image.planes[c].data(), sizeof(float), rowBytes));
    // OpenEXR compresses its 16-line blocks in its global thread pool, which is empty unless set
    // (then the writing thread compresses every block itself): a 512x512 4-spp render with the
    // sobol sub-sequence layers (26 float channels) spent half its process in ZIP on one core.
    // The file's bytes do not depend on the thread count.
    const int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    if (Imf::globalThreadCount() < threads) Imf::setGlobalThreadCount(threads);
    Imf::OutputFile out(path.c_str(), header, threads);
    out.setFrameBuffer(frame);
    out.writePixels(image.height);
  } catch (const std::exception& e) {
    throw RuntimeError("cannot write " + displayPath + ": " + e.what());
  }
}

}  // namespace montecl
