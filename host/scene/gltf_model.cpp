// gltf_model.cpp: tinygltf with montecl's file callbacks, and checked accessor reads (see
// gltf_model.h).
#include "scene/gltf_model.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "scene/gltf_draco.h"
#include "scene/gltf_material.h"
#include "scene/gltf_transmission.h"
#include "scene/load_util.h"

namespace montecl {
namespace {

bool fileExists(const std::string& path, void*) { return fileProblem(path).empty(); }
std::string expandNothing(const std::string& path, void*) { return path; }

// user: the caller's list of opened files (the paths as tinygltf decoded and opened them), or null.
bool readFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  const std::string problem = fileProblem(path);
  if (!problem.empty()) {
    if (err) *err += "cannot open '" + path + "': " + problem + "\n";
    return false;
  }
  try {
    const std::string bytes = readWholeFile(path);
    out->assign(bytes.begin(), bytes.end());
    if (user) static_cast<std::vector<std::string>*>(user)->push_back(path);
  } catch (const std::exception& e) {
    if (err) *err += std::string(e.what()) + "\n";
    return false;
  }
  return true;
}

bool writeNothing(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "montecl writes no files while loading\n";
  return false;
}

// Images are decoded later, by the texture loader: an image in a file of its own is opened there by
// path (its bytes are dropped here); a data URI's (no uri is kept for it) keeps its decoded bytes in
// image->image until gltfImagePath hands them to the scene. A bufferView's bytes are not taken
// here: tinygltf passes its byteLength unchecked against the buffer, so gltfImagePath reads the
// view itself, bounds checked.
bool keepImageUndecoded(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                        const unsigned char* bytes, int size, void*) {
  if (image->bufferView < 0 && (image->uri.empty() || image->uri.compare(0, 5, "data:") == 0) && bytes && size > 0) {
    image->image.assign(bytes, bytes + size);
    image->as_is = true;
  }
  return true;
}

// The file-name extension OpenImageIO picks its reader by, for an embedded image: from its
// mimeType, else from the bytes' signature; empty when neither names a format montecl reads.
std::string embeddedImageExtension(const tinygltf::Image& img) {
  if (img.mimeType == "image/png") return "png";
  if (img.mimeType == "image/jpeg") return "jpg";
  const std::vector<unsigned char>& b = img.image;
  if (b.size() >= 8 && b[0] == 0x89 && b[1] == 'P' && b[2] == 'N' && b[3] == 'G') return "png";
  if (b.size() >= 3 && b[0] == 0xff && b[1] == 0xd8 && b[2] == 0xff) return "jpg";
  return "";
}

std::string firstLine(const std::string& s) {
  std::string line = s.substr(0, s.find('\n'));
  return line.empty() ? "cannot parse glTF" : line;
}

// tinygltf's error line as montecl's "<file>: <where>: <problem>".
[[noreturn]] void failWith(const std::string& path, std::string err, bool glb) {
  const std::string json = "[json.exception.parse_error.101] parse error at ", missing = "File not found : ";
  if (err.compare(0, json.size(), json) == 0) {
    err.erase(0, json.size());
    const std::size_t colon = err.find(": ");
    if (colon != std::string::npos) loadFail(path, err.substr(0, colon), "not valid glTF JSON: " + err.substr(colon + 2));
  }
  if (err.compare(0, missing.size(), missing) == 0)
    loadFail(path, "buffers", "cannot open '" + besideFile(path, err.substr(missing.size())) + "': no such file");
  if (!err.empty() && err.back() == '.') err.pop_back();
  loadFail(path, "", (glb ? "not a valid GLB: " : "not a valid glTF: ") + err);
}

int hexValue(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

std::string percentDecode(const std::string& s) {
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '%' && i + 2 < s.size() && hexValue(s[i + 1]) >= 0 && hexValue(s[i + 2]) >= 0) {
      out += static_cast<char>(hexValue(s[i + 1]) * 16 + hexValue(s[i + 2]));
      i += 2;
    } else {
      out += s[i];
    }
  }
  return out;
}

// The bytes of an accessor's elements, checked to lie inside its buffer: returns a pointer to
// element 0 and the stride; elementBytes is the size of one element.
const unsigned char* accessorBytes(const std::string& file, const tinygltf::Model& m, const tinygltf::Accessor& a,
                                   std::size_t elementBytes, std::size_t& stride, const std::string& where) {
  if (a.sparse.isSparse) loadFail(file, where, "sparse accessors are not supported");
  if (a.bufferView < 0 || static_cast<std::size_t>(a.bufferView) >= m.bufferViews.size())
    loadFail(file, where, "accessor without a valid bufferView");
  const tinygltf::BufferView& v = m.bufferViews[static_cast<std::size_t>(a.bufferView)];
  if (v.buffer < 0 || static_cast<std::size_t>(v.buffer) >= m.buffers.size())
    loadFail(file, where, "bufferView " + std::to_string(a.bufferView) + " names no valid buffer");
  const std::vector<unsigned char>& data = m.buffers[static_cast<std::size_t>(v.buffer)].data;
  stride = v.byteStride ? v.byteStride : elementBytes;
  if (stride < elementBytes) loadFail(file, where, "byteStride smaller than one element");
  const std::size_t viewEnd = v.byteOffset + v.byteLength;
  if (v.byteOffset > data.size() || v.byteLength > data.size() - v.byteOffset)
    loadFail(file, where, "bufferView " + std::to_string(a.bufferView) + " runs past the end of its buffer");
  if (a.count == 0) return data.data();
  const std::size_t start = v.byteOffset + a.byteOffset;
  const std::size_t span = (a.count - 1) > (std::numeric_limits<std::size_t>::max() - elementBytes) / stride
                               ? std::numeric_limits<std::size_t>::max()
                               : (a.count - 1) * stride + elementBytes;
  if (a.byteOffset > v.byteLength || span > viewEnd - start)
    loadFail(file, where, "accessor runs past the end of its bufferView (" + std::to_string(a.count) + " elements)");
  return data.data() + start;
}

const tinygltf::Accessor& accessorAt(const std::string& file, const tinygltf::Model& m, int index,
                                     const std::string& where) {
  if (index < 0 || static_cast<std::size_t>(index) >= m.accessors.size())
    loadFail(file, where, "accessor index " + std::to_string(index) + " out of range");
  return m.accessors[static_cast<std::size_t>(index)];
}

// What tinygltf accepts silently but montecl must not: it reads a negative byteOffset as 0 and a
// %00 in a URI would cut the path at the NUL. Checked on the JSON text itself (depth-checked before).
void checkGltfJson(const std::string& path, const char* text, std::size_t size) {
  const nlohmann::json j = nlohmann::json::parse(text, text + size, nullptr, false);
  if (!j.is_object()) return;  // tinygltf reports the parse error with its position
  const auto each = [&](const char* array, const auto& check) {
    const auto it = j.find(array);
    if (it == j.end() || !it->is_array()) return;
    for (std::size_t i = 0; i < it->size(); ++i)
      if ((*it)[i].is_object()) check((*it)[i], std::string(array) + "[" + std::to_string(i) + "]");
  };
  const auto wholeNumbers = [&](const nlohmann::json& o, const std::string& where, std::initializer_list<const char*> keys) {
    for (const char* key : keys) {
      const auto it = o.find(key);
      if (it != o.end() && !it->is_number_unsigned())
        loadFail(path, where + "." + key, "must be a whole number >= 0 (got " + oneLine(it->dump(), 40) + ")");
    }
  };
  each("bufferViews", [&](const nlohmann::json& o, const std::string& w) { wholeNumbers(o, w, {"byteOffset", "byteLength", "byteStride"}); });
  each("accessors", [&](const nlohmann::json& o, const std::string& w) { wholeNumbers(o, w, {"byteOffset", "count"}); });
  const auto noNul = [&](const nlohmann::json& o, const std::string& where) {
    const auto it = o.find("uri");
    if (it == o.end() || !it->is_string()) return;
    std::string uri = it->get<std::string>();
    for (char& c : uri) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (uri.compare(0, 5, "data:") != 0 && uri.find("%00") != std::string::npos)
      loadFail(path, where + ".uri", "contains %00 (a NUL byte): not a file name");
  };
  // A required extension montecl does not read changes what the file means: refused, by name,
  // before tinygltf reports what it trips over instead (e.g. meshopt's accessors hold no data).
  if (const auto req = j.find("extensionsRequired"); req != j.end() && req->is_array())
    for (std::size_t i = 0; i < req->size(); ++i) {
      const std::string name = (*req)[i].is_string() ? (*req)[i].get<std::string>() : (*req)[i].dump();
      if (gltfExtensionSupported(name)) continue;
      loadFail(path, "extensionsRequired[" + std::to_string(i) + "]",
               "extension '" + oneLine(name, 60) + "' is required by the file and not supported by montecl");
    }
  each("images", noNul);
  each("buffers", noNul);
  each("materials", [&](const nlohmann::json& o, const std::string& w) {
    // tinygltf keeps the default 1 for a normalTexture scale that is not a number.
    if (const auto nt = o.find("normalTexture"); nt != o.end() && nt->is_object())
      if (const auto sc = nt->find("scale"); sc != nt->end() && !sc->is_number())
        loadFail(path, w + ".normalTexture.scale", "must be a number (got " + oneLine(sc->dump(), 40) + ")");
    const auto ext = o.find("extensions");
    if (ext == o.end() || !ext->is_object()) return;
    const auto es = ext->find("KHR_materials_emissive_strength");
    if (es == ext->end() || !es->is_object()) return;
    const auto v = es->find("emissiveStrength");
    if (v != es->end() && !v->is_number())
      loadFail(path, w + ".extensions.KHR_materials_emissive_strength.emissiveStrength",
               "must be a number (got " + oneLine(v->dump(), 40) + ")");
  });
}

}  // namespace

tinygltf::Model readGltfModel(const std::string& path, std::vector<std::string>* warnings,
                              std::vector<std::string>* opened) {
  std::string bytes = readWholeFile(path);
  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks({&fileExists, &expandNothing, &readFile, &writeNothing, opened});
  loader.SetImageLoader(&keepImageUndecoded, nullptr);
  tinygltf::Model model;
  std::string err, warn;
  const std::string dir = folderOf(path).empty() ? "." : folderOf(path);
  const bool glb = bytes.compare(0, 4, "glTF") == 0;
  if (glb && bytes.size() >= 20) {  // the JSON chunk: length at byte 12, text from byte 20
    std::uint32_t version = 0, length = 0;
    std::memcpy(&version, bytes.data() + 4, 4);
    if (version != 2)  // GLB 1 (KHR_binary_glTF) has another layout; tinygltf reads it as 2
      loadFail(path, "header", "GLB version " + std::to_string(version) + " (only version 2 is supported)");
    std::memcpy(&length, bytes.data() + 12, 4);
    checkJsonDepth(path, bytes.data() + 20, std::min<std::size_t>(length, bytes.size() - 20));
    checkGltfJson(path, bytes.data() + 20, std::min<std::size_t>(length, bytes.size() - 20));
    // tinygltf checks the BIN chunk's length against the GLB header's total but forgets the chunk's
    // own 8-byte header, so a length that fills the file to the end is read past it: check it here.
    std::uint32_t total = 0;
    std::memcpy(&total, bytes.data() + 8, 4);
    const std::uint64_t binAt = 20ull + length;  // where the BIN chunk's header starts
    if (total > binAt && binAt + 8 <= bytes.size()) {
      std::uint32_t binLength = 0;
      std::memcpy(&binLength, bytes.data() + binAt, 4);
      if (binAt + 8 + binLength > bytes.size())
        loadFail(path, "BIN chunk", "claims " + std::to_string(binLength) + " bytes but the file holds only " +
                                        std::to_string(bytes.size() - binAt - 8) + " after its header");
    }
  } else if (!glb) {
    checkJsonDepth(path, bytes.data(), bytes.size());
    checkGltfJson(path, bytes.data(), bytes.size());
  }
  std::vector<GltfHiddenIndices> hidden;  // Draco primitives' indices, kept from tinygltf (gltf_draco.h)
  if (glb) hideGltfDracoIndicesInGlb(bytes, hidden);
  else hideGltfDracoIndices(bytes, hidden);
  bool ok = false;
  if (glb) {
    try {
      ok = loader.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(bytes.data()),
                                       static_cast<unsigned int>(bytes.size()), dir);
    } catch (const std::out_of_range&) {
      // tinygltf copies a BIN-chunk buffer with data.at(0), which throws for byteLength 0; the
      // buffers parsed so far say which one it was.
      loadFail(path, "buffers[" + std::to_string(model.buffers.size()) + "]",
               "byteLength 0: a buffer stored in the BIN chunk must hold at least one byte");
    }
  } else {
    if (lowerExtension(path) == ".glb") loadFail(path, "", "not a binary glTF (no 'glTF' magic)");
    ok = loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(), static_cast<unsigned int>(bytes.size()), dir);
  }
  if (!ok || !err.empty()) failWith(path, firstLine(err), glb);
  restoreGltfDracoIndices(model, hidden);
  // An image file tinygltf cannot find is the loader's to report (every missing texture in one
  // listing, missing_textures): its "File not found" and "Failed to load external 'uri' for
  // image" lines are dropped here.
  std::string kept;
  for (std::size_t p = 0; p < warn.size();) {
    std::size_t eol = warn.find('\n', p);
    if (eol == std::string::npos) eol = warn.size();
    const std::string line = warn.substr(p, eol - p);
    const bool image = line.compare(0, 17, "File not found : ") == 0 ||
                       line.compare(0, 39, "Failed to load external 'uri' for image") == 0;
    if (!line.empty() && !image) kept += line + "\n";
    p = eol + 1;
  }
  if (warnings && !kept.empty()) warnings->push_back(oneLine(path) + ": " + oneLine(firstLine(kept)));
  return model;
}

bool gltfExtensionSupported(const std::string& name) {
  return gltfMaterialExtensionRead(name) || name == "KHR_lights_punctual" || name == "KHR_mesh_quantization" ||
         name == "EXT_mesh_gpu_instancing" || name == "KHR_texture_transform" || name == "KHR_draco_mesh_compression";
}

const tinygltf::Accessor& checkFloatAccessor(const std::string& file, const tinygltf::Model& m, int index, int components,
                                             const std::string& where, AccessorUse use) {
  const tinygltf::Accessor& a = accessorAt(file, m, index, where);
  const int type = components == 2 ? TINYGLTF_TYPE_VEC2 : components == 4 ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3;
  if (a.type != type) loadFail(file, where, "expected a VEC" + std::to_string(components) + " accessor");
  const int ct = a.componentType;
  const bool isFloat = ct == TINYGLTF_COMPONENT_TYPE_FLOAT;
  const bool isSigned = ct == TINYGLTF_COMPONENT_TYPE_BYTE || ct == TINYGLTF_COMPONENT_TYPE_SHORT;
  const bool isUnsigned = ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE || ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
  bool allowed = isFloat || (a.normalized && isUnsigned);  // core glTF
  const char* rule = "FLOAT (or normalized unsigned byte / short)";
  if (use == AccessorUse::Position || use == AccessorUse::TexCoord) {
    allowed = isFloat || isSigned || isUnsigned;
    rule = "FLOAT or (KHR_mesh_quantization) byte / short, signed or unsigned, normalized or not";
  } else if (use == AccessorUse::Normal) {
    allowed = isFloat || (a.normalized && isSigned);
    rule = "FLOAT or (KHR_mesh_quantization) normalized signed byte / short";
  }
  if (!allowed) loadFail(file, where, std::string("expected ") + rule + " components");
  return a;
}

float gltfIntegerComponent(float v, int componentType, bool normalized) {
  if (!normalized) return v;
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return std::max(v / 127.0f, -1.0f);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return v / 255.0f;
    case TINYGLTF_COMPONENT_TYPE_SHORT: return std::max(v / 32767.0f, -1.0f);
    default: return v / 65535.0f;
  }
}

std::vector<float> readFloatAccessor(const std::string& file, const tinygltf::Model& m, int index, int components,
                                     const std::string& where, AccessorUse use) {
  const tinygltf::Accessor& a = checkFloatAccessor(file, m, index, components, where, use);
  const int ct = a.componentType;
  const bool isFloat = ct == TINYGLTF_COMPONENT_TYPE_FLOAT;
  const bool isSigned = ct == TINYGLTF_COMPONENT_TYPE_BYTE || ct == TINYGLTF_COMPONENT_TYPE_SHORT;
  const std::size_t size = static_cast<std::size_t>(tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(ct)));
  std::size_t stride = 0;
  const unsigned char* p = accessorBytes(file, m, a, size * components, stride, where);
  std::vector<float> out(a.count * static_cast<std::size_t>(components));
  for (std::size_t i = 0; i < a.count; ++i)
    for (int c = 0; c < components; ++c) {
      const unsigned char* q = p + i * stride + static_cast<std::size_t>(c) * size;
      float f = 0.0f;
      if (isFloat) {
        std::memcpy(&f, q, 4);
      } else if (size == 1) {
        f = gltfIntegerComponent(isSigned ? float(std::int8_t(*q)) : float(*q), ct, a.normalized);
      } else {
        std::uint16_t u;
        std::memcpy(&u, q, 2);
        f = gltfIntegerComponent(isSigned ? float(std::int16_t(u)) : float(u), ct, a.normalized);
      }
      if (!std::isfinite(f)) loadFail(file, where, "element " + std::to_string(i) + " is not finite");
      out[i * static_cast<std::size_t>(components) + static_cast<std::size_t>(c)] = f;
    }
  return out;
}

std::vector<std::uint32_t> readIndexAccessor(const std::string& file, const tinygltf::Model& m, int index,
                                             const std::string& where) {
  const tinygltf::Accessor& a = accessorAt(file, m, index, where);
  if (a.type != TINYGLTF_TYPE_SCALAR) loadFail(file, where, "indices must be a SCALAR accessor");
  const int ct = a.componentType;
  std::size_t size = ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ? 1 : ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 2
                   : ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT ? 4 : 0;
  if (size == 0) loadFail(file, where, "indices must be UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT");
  std::size_t stride = 0;
  const unsigned char* p = accessorBytes(file, m, a, size, stride, where);
  std::vector<std::uint32_t> out(a.count);
  for (std::size_t i = 0; i < a.count; ++i) {
    std::uint32_t v = 0;
    if (size == 1) v = p[i * stride];
    else if (size == 2) {
      std::uint16_t s;
      std::memcpy(&s, p + i * stride, 2);
      v = s;
    } else std::memcpy(&v, p + i * stride, 4);
    out[i] = v;
  }
  return out;
}

GltfViewBytes gltfBufferViewBytes(const std::string& file, const tinygltf::Model& m, int index, const std::string& where) {
  if (index < 0 || static_cast<std::size_t>(index) >= m.bufferViews.size())
    loadFail(file, where, "bufferView " + std::to_string(index) + " out of range");
  const tinygltf::BufferView& v = m.bufferViews[static_cast<std::size_t>(index)];
  if (v.buffer < 0 || static_cast<std::size_t>(v.buffer) >= m.buffers.size())
    loadFail(file, where, "bufferView " + std::to_string(index) + " names no valid buffer");
  const std::vector<unsigned char>& data = m.buffers[static_cast<std::size_t>(v.buffer)].data;
  if (v.byteOffset > data.size() || v.byteLength > data.size() - v.byteOffset)
    loadFail(file, where, "bufferView " + std::to_string(index) + " runs past the end of its buffer");
  return {data.data() + v.byteOffset, v.byteLength};
}

std::string gltfImagePath(const std::string& file, const tinygltf::Model& m, int index, Scene& scene) {
  if (index < 0 || static_cast<std::size_t>(index) >= m.images.size()) return "";
  const tinygltf::Image& img = m.images[static_cast<std::size_t>(index)];
  const std::string where = "images[" + std::to_string(index) + "]";
  if (!img.uri.empty() && img.uri.compare(0, 5, "data:") != 0 && img.bufferView < 0)
    return besideFile(file, percentDecode(img.uri));
  tinygltf::Image held = img;  // the bytes: a data URI's as decoded, or the bufferView's
  if (img.bufferView >= 0) {
    const GltfViewBytes bytes = gltfBufferViewBytes(file, m, img.bufferView, where);
    held.image.assign(bytes.data, bytes.data + bytes.size);
  }
  if (held.image.empty()) loadFail(file, where, "embedded image holds no bytes");
  const std::string ext = embeddedImageExtension(held);
  if (ext.empty())
    loadFail(file, where, "embedded image of type '" + img.mimeType + "': montecl reads PNG and JPEG images");
  const std::string name = file + "#" + where + "." + ext;
  scene.embeddedImages.emplace(name, std::move(held.image));
  return name;
}

}  // namespace montecl
