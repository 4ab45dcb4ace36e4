// exr_read.cpp: an OpenEXR file or encoded bytes -> float planes with OpenEXR (exr_read.h).
#include "image/exr_read.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputPart.h>
#include <ImfMultiPartInputFile.h>
#include <ImfPartType.h>
#include <ImfStringAttribute.h>
#include <Iex.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <exception>
#include <fstream>
#include <istream>
#include <streambuf>
#include <vector>

#include "image/exr_layers.h"
#include "image/image_limits.h"

namespace montecl {
namespace {

// The encoded bytes as OpenEXR's input stream (an EXR inside a .glb or a data URI).
class ExrMemoryStream : public Imf::IStream {
 public:
  ExrMemoryStream(const unsigned char* data, std::size_t size) : Imf::IStream("memory"), data_(data), size_(size) {}
  bool read(char c[], int n) override {
    if (n < 0 || std::size_t(n) > size_ - pos_) throw Iex::InputExc("file is truncated");
    std::memcpy(c, data_ + pos_, std::size_t(n));
    pos_ += std::size_t(n);
    return pos_ < size_;
  }
  uint64_t tellg() override { return pos_; }
  void seekg(uint64_t pos) override { pos_ = std::size_t(std::min<uint64_t>(pos, size_)); }

 private:
  const unsigned char* data_;
  std::size_t size_, pos_ = 0;
};

// OpenImageIO's canonical channel order: by layer (the name up to and including its last dot; no
// layer first), within a layer the reserved names in the order of one of two lists (any case),
// then the rest by name. A layer with X and Y or Z (a position or a normal: montecl's N.X/Y/Z)
// takes the second list, where X Y Z come before alpha; the first keeps Y with the colours and Z
// (depth) after alpha. montecl's AOV files, textures and environment maps read in this order, as
// they did through OpenImageIO.
struct ExrChannelKey {
  std::string name, layer, suffix;
  int special = 10000;
};

bool exrIequals(const std::string& a, const char* b) {
  if (a.size() != std::strlen(b)) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::tolower((unsigned char)a[i]) != std::tolower((unsigned char)b[i])) return false;
  return true;
}

ExrChannelKey exrChannelKey(const std::string& name) {
  ExrChannelKey k;
  k.name = name;
  const std::size_t dot = name.find_last_of('.');
  k.layer = dot == std::string::npos ? "" : name.substr(0, dot + 1);
  k.suffix = dot == std::string::npos ? name : name.substr(dot + 1);
  return k;
}

// Sets every key's place in its layer's list of reserved names.
void setExrSpecialIndices(std::vector<ExrChannelKey>& keys) {
  static const std::vector<const char*> usual = {"R",  "Red", "G",  "Green", "B",  "Blue",  "Y",
                                                 "real", "imag", "A", "Alpha", "AR", "RA", "AG",
                                                 "GA", "AB",  "BA", "Z",     "Depth", "Zback"};
  static const std::vector<const char*> xyz = {"R",  "Red", "G",  "Green", "B",  "Blue", "X",
                                               "Y",  "Z",   "real", "imag", "A", "Alpha", "AR",
                                               "RA", "AG",  "GA", "AB",    "BA", "Depth", "Zback"};
  const auto layerHas = [&](const std::string& layer, const char* suffix) {
    for (const ExrChannelKey& k : keys)
      if (k.layer == layer && exrIequals(k.suffix, suffix)) return true;
    return false;
  };
  for (ExrChannelKey& k : keys) {
    const bool position = layerHas(k.layer, "X") && (layerHas(k.layer, "Y") || layerHas(k.layer, "Z"));
    const std::vector<const char*>& list = position ? xyz : usual;
    for (std::size_t i = 0; i < list.size(); ++i)
      if (exrIequals(k.suffix, list[i])) {
        k.special = int(i);
        break;
      }
  }
}

// A luminance-chroma image (Y, BY, RY and maybe A or Alpha, nothing else), which OpenImageIO
// converts to RGB itself.
bool isExrLuminanceChroma(const std::vector<ExrChannelKey>& keys) {
  if (keys.size() < 3 || keys.size() > 4) return false;
  const auto has = [&](const char* suffix) {
    for (const ExrChannelKey& k : keys)
      if (exrIequals(k.suffix, suffix)) return true;
    return false;
  };
  return has("Y") && has("BY") && has("RY") && (keys.size() == 3 || has("A") || has("Alpha"));
}

bool exrChannelBefore(const ExrChannelKey& a, const ExrChannelKey& b) {
  if (a.layer != b.layer) return a.layer < b.layer;
  if (a.special != b.special) return a.special < b.special;
  return a.suffix < b.suffix;
}

std::string exrOneLine(std::string message) {
  for (char& c : message)
    if (c == '\n' || c == '\r') c = ' ';
  while (!message.empty() && message.back() == ' ') message.pop_back();
  return message.empty() ? "OpenEXR error" : message;
}

// Walks the attribute list of an OpenEXR file's header(s) (name\0 type\0 int32 size, value) and
// refuses sizes beyond the end of the file before OpenEXR sees them: OpenEXR 3.1 allocates and
// clears an attribute's declared size first (a flipped byte made it take 2 GB and 2-3 s per
// file; found by fuzzing, docs/fuzzing.md). in is at the start of a file of fileSize bytes that
// has OpenEXR's magic number. "" when every attribute fits.
// An attribute name as read from the file, fit for a one-line message: bytes outside printable
// ASCII as \xNN (a corrupt name may hold a newline), at most 64 of them.
std::string printableName(const std::string& name) {
  static const char kHex[] = "0123456789abcdef";
  std::string out;
  for (std::size_t i = 0; i < name.size() && i < 64; ++i) {
    const unsigned char c = static_cast<unsigned char>(name[i]);
    if (c >= 0x20 && c < 0x7f) {
      out.push_back(char(c));
    } else {
      out += "\\x";
      out.push_back(kHex[c >> 4]);
      out.push_back(kHex[c & 15]);
    }
  }
  return name.size() > 64 ? out + "..." : out;
}

std::string exrHeaderProblem(std::istream& in, std::int64_t fileSize) {
  unsigned char start[8] = {0};
  if (!in.read(reinterpret_cast<char*>(start), 8)) return "corrupt EXR header: truncated";
  const bool multipart = (start[5] & 0x10) != 0;  // version field bit 12
  std::string why;
  auto readString = [&](std::string& s) {
    s.clear();
    for (char c; in.get(c);) {
      if (c == '\0') return true;
      if (s.size() >= 255) {
        why = "attribute name or type longer than 255 bytes";
        return false;
      }
      s.push_back(c);
    }
    why = "truncated";
    return false;
  };
  for (int header = 0;; ++header) {
    std::string name, type;
    int attributes = 0;
    while (true) {
      if (!readString(name)) return "corrupt EXR header: " + why;
      if (name.empty()) break;
      if (!readString(type)) return "corrupt EXR header: " + why;
      unsigned char sz[4];
      if (!in.read(reinterpret_cast<char*>(sz), 4)) return "corrupt EXR header: truncated";
      const std::int32_t size = std::int32_t(std::uint32_t(sz[0]) | std::uint32_t(sz[1]) << 8 |
                                             std::uint32_t(sz[2]) << 16 | std::uint32_t(sz[3]) << 24);
      const std::int64_t pos = static_cast<std::int64_t>(in.tellg());
      if (size < 0 || pos < 0 || size > fileSize - pos)
        return "corrupt EXR header: attribute '" + printableName(name) + "' claims " + std::to_string(size) +
               " bytes, past the end of the file";
      in.seekg(size, std::ios::cur);
      ++attributes;
    }
    if (!multipart || attributes == 0 || header > 1000) return "";
    if (in.peek() == 0) return "";  // the empty header that ends a multi-part header list
  }
}

// Encoded bytes as a std::istream's buffer, for exrHeaderProblem.
struct ExrByteBuffer : std::streambuf {
  ExrByteBuffer(const unsigned char* data, std::size_t size) {
    char* b = const_cast<char*>(reinterpret_cast<const char*>(data));
    setg(b, b, b + size);
  }
  pos_type seekoff(off_type off, std::ios_base::seekdir dir, std::ios_base::openmode) override {
    const off_type base = dir == std::ios_base::beg ? 0 : dir == std::ios_base::cur ? gptr() - eback() : egptr() - eback();
    const off_type to = base + off;
    if (to < 0 || to > egptr() - eback()) return pos_type(off_type(-1));
    setg(eback(), eback() + to, egptr());
    return pos_type(to);
  }
  pos_type seekpos(pos_type pos, std::ios_base::openmode mode) override {
    return seekoff(off_type(pos), std::ios_base::beg, mode);
  }
};

// The most decoded float bytes one byte of a part can give, by its compression's best case on
// half data (decoded to 4-byte floats, twice the stored bytes): raw 2; RLE 2 bytes per 128-byte
// run; zlib (ZIP, ZIPS, PXR24) about 1032:1; PIZ's run-length Huffman codes, B44's flat blocks;
// DWA's DCT blocks then zlib, and any other, 2^17.
std::uint64_t exrMaxRatio(Imf::Compression c, std::string& name) {
  switch (c) {
    case Imf::NO_COMPRESSION: name = "no"; return 2;
    case Imf::RLE_COMPRESSION: name = "RLE"; return 256;
    case Imf::ZIPS_COMPRESSION: case Imf::ZIP_COMPRESSION: case Imf::PXR24_COMPRESSION: name = "zlib"; return 4096;
    case Imf::PIZ_COMPRESSION: name = "PIZ"; return 4096;
    case Imf::B44_COMPRESSION: case Imf::B44A_COMPRESSION: name = "B44"; return 64;
    default: name = "DWA or other"; return std::uint64_t(1) << 17;
  }
}

std::string decodeExrPart(Imf::MultiPartInputFile& file, LayeredImage& out, const ImageSizeCheck& check,
                          bool& unsupported, std::int64_t fileSize) {
  const Imf::Header& header = file.header(0);
  if (header.hasType() && Imf::isDeepData(header.type())) return "deep images are not supported";
  std::vector<ExrChannelKey> keys;
  bool anyHalf = false, anyFloat = false, anyUint = false;
  std::string subsampled;
  for (auto c = header.channels().begin(); c != header.channels().end(); ++c) {
    const Imf::Channel& ch = c.channel();
    if ((ch.xSampling != 1 || ch.ySampling != 1) && subsampled.empty()) subsampled = c.name();
    (ch.type == Imf::HALF ? anyHalf : ch.type == Imf::FLOAT ? anyFloat : anyUint) = true;
    keys.push_back(exrChannelKey(c.name()));
  }
  if (isExrLuminanceChroma(keys) || anyUint) {
    unsupported = true;
    return "";
  }
  if (!subsampled.empty()) return "subsampled channels are not supported (channel \"" + subsampled + "\")";
  setExrSpecialIndices(keys);
  std::sort(keys.begin(), keys.end(), exrChannelBefore);
  const Imath::Box2i& window = header.dataWindow();
  const long w = long(window.max.x) - window.min.x + 1, h = long(window.max.y) - window.min.y + 1;
  std::string refused = imageSizeProblem(w, h, int(keys.size()), window.min.x, window.min.y);
  if (refused.empty()) {
    std::string compression;
    const std::uint64_t ratio = exrMaxRatio(header.compression(), compression);
    refused = fileSizeProblem(std::uint64_t(w) * std::uint64_t(h) * keys.size() * 4u, std::uint64_t(fileSize), ratio,
                              compression);
  }
  if (refused.empty() && check) refused = check(int(w), int(h), int(keys.size()));
  if (!refused.empty()) return refused;
  LayeredImage image;
  image.width = int(w);
  image.height = int(h);
  image.pixelType = anyHalf && !anyFloat ? "half" : "float";
  Imf::FrameBuffer frame;
  const std::size_t rowBytes = sizeof(float) * std::size_t(w);
  for (const ExrChannelKey& k : keys) {
    image.channels.push_back(k.name);
    image.planes.emplace_back(image.pixelCount());
    frame.insert(k.name, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(image.planes.back().data()), sizeof(float),
                                    rowBytes));
  }
  Imf::InputPart part(file, 0);
  part.setFrameBuffer(frame);
  part.readPixels(window.min.y, window.max.y);
  for (auto a = header.begin(); a != header.end(); ++a)
    if (std::strncmp(a.name(), "montecl:", 8) == 0)
      if (const auto* s = dynamic_cast<const Imf::StringAttribute*>(&a.attribute())) image.attributes[a.name()] = s->value();
  out = std::move(image);
  return "";
}

}  // namespace

bool isExrSignature(const unsigned char* data, std::size_t size) {
  return size >= 4 && data[0] == 0x76 && data[1] == 0x2f && data[2] == 0x31 && data[3] == 0x01;
}

std::string decodeExr(const std::string& path, const unsigned char* data, std::size_t size, LayeredImage& out,
                      const ImageSizeCheck& check, bool& unsupported) {
  out = LayeredImage{};
  unsupported = false;
  try {
    if (data) {
      if (!isExrSignature(data, size)) return "not an OpenEXR file";
      ExrByteBuffer buffer(data, size);
      std::istream header(&buffer);
      if (std::string why = exrHeaderProblem(header, std::int64_t(size)); !why.empty()) return why;
      ExrMemoryStream stream(data, size);
      Imf::MultiPartInputFile file(stream);
      return decodeExrPart(file, out, check, unsupported, std::int64_t(size));
    }
    unsigned char head[4] = {0};
    std::ifstream in(path, std::ios::binary);
    if (!in) return "cannot open the file";
    in.read(reinterpret_cast<char*>(head), 4);
    if (!isExrSignature(head, std::size_t(in.gcount()))) return "not an OpenEXR file";
    in.seekg(0, std::ios::end);
    const std::int64_t fileSize = static_cast<std::int64_t>(in.tellg());
    in.seekg(0);
    if (std::string why = exrHeaderProblem(in, fileSize); !why.empty()) return why;
    in.close();
    Imf::MultiPartInputFile file(path.c_str());
    return decodeExrPart(file, out, check, unsupported, fileSize);
  } catch (const std::exception& e) {  // OpenEXR reports a corrupt or truncated file by throwing
    out = LayeredImage{};
    return exrOneLine(e.what());
  }
}

}  // namespace montecl
