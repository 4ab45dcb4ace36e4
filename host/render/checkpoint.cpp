// checkpoint.cpp: render/checkpoint.h's binary film file.
#include "render/checkpoint.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <fstream>

#include "render/frame_params.h"
#include "render/integrators.h"
#include "scene/scene_digest.h"
#include "util/atomic_file.h"
#include "util/errors.h"
#include "util/hash.h"

namespace montecl {
namespace {

constexpr char kCheckpointMagic[8] = {'M', 'C', 'L', 'C', 'K', 'P', 'T', '1'};
constexpr std::uint32_t kVersion = 1;

struct Header {
  char magic[8];
  std::uint32_t version, headerBytes;
  std::uint64_t key;
  std::uint32_t width, height, aovs, seed, spp, firstSample, integrator, minSpp, maxSpp, splits;
  double targetError;
  std::uint64_t samplesDone, payloadHash;
};
static_assert(sizeof(Header) == 88, "checkpoint header layout");

template <class T>
void append(std::string& out, const T* data, std::size_t n) {
  out.append(reinterpret_cast<const char*>(data), n * sizeof(T));
}

std::string payloadOf(const Film& film, bool aovs, bool adaptive) {
  std::string out;
  const std::size_t n = film.pixelCount();
  for (const auto* v : {&film.mean, &film.meanLo, &film.m2, &film.m2Lo}) append(out, v->data(), n);
  append(out, film.count.data(), n);
  if (aovs) append(out, film.aovSum.data(), MCL_AOV_VECTORS * n);
  append(out, film.split.data(), film.split.size());
  if (adaptive) {  // a film read before the first round has none yet: its targets are its counts
    const std::vector<std::uint64_t>& t = film.roundTarget.size() == n ? film.roundTarget : film.count;
    append(out, t.data(), n);
  }
  return out;
}

}  // namespace

std::uint64_t renderKey(const Scene& scene, const RenderOptions& o) {
  const std::uint32_t slots = integratorDesc(scene.render.integrator).shadowSlots(scene.render);
  FrameParams f = makeFrameParams(scene.camera, scene.render, slots);
  f.activeCount = 0;
  // One render identity with the provenance of an EXR (image/provenance.h): the scene digest
  // (geometry, every material field, texture and environment contents, camera) and the settings
  // string, then what only a checkpoint needs (the frame as uploaded, sampling, AOVs).
  Fnv1a64 h;
  h.add(sceneDigest(scene) + '\0' + integratorSettings(scene.render) + '\0' + o.identityExtra + '\0');
  h.add(&f, sizeof f);
  const std::uint32_t ints[] = {std::uint32_t(scene.render.integrator), std::uint32_t(scene.render.spp),
                                o.firstSample, std::uint32_t(o.minSpp), std::uint32_t(o.maxSpp), o.aovs};
  h.add(ints, sizeof ints);
  const double reals[] = {o.targetError > 0.0 ? o.targetError : 0.0, o.targetError > 0.0 ? o.errorFloor : 0.0};
  h.add(reals, sizeof reals);
  return h.value();
}

CheckpointInfo checkpointInfo(const Scene& scene, const RenderOptions& options) {
  CheckpointInfo info;
  info.key = renderKey(scene, options);
  info.seed = scene.render.seed;
  info.spp = std::uint32_t(scene.render.spp);
  info.firstSample = options.firstSample;
  info.aovs = options.aovs;
  info.adaptive = scene.render.adaptive;
  return info;
}

void writeCheckpoint(const std::string& path, const CheckpointInfo& info, const Film& film) {
  Header h{};
  std::memcpy(h.magic, kCheckpointMagic, 8);
  h.version = kVersion;
  h.headerBytes = sizeof(Header);
  h.key = info.key;
  h.width = std::uint32_t(film.width);
  h.height = std::uint32_t(film.height);
  h.aovs = info.aovs ? MCL_AOV_VECTORS : 0;
  h.seed = info.seed;
  h.spp = info.spp;
  h.firstSample = info.firstSample;
  h.splits = std::uint32_t(film.splits());
  for (std::uint64_t c : film.count) h.samplesDone += c;
  const std::string payload = payloadOf(film, info.aovs, info.adaptive);
  h.payloadHash = fnv1a64(payload);
  writeAtomically(path, [&](const std::string& tmp) {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(&h), sizeof h);
    out.write(payload.data(), std::streamsize(payload.size()));
    out.flush();
    if (!out) throw RuntimeError("cannot write checkpoint " + path);
  });
}

bool isCheckpointFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char magic[8] = {};
  return in.read(magic, 8) && std::memcmp(magic, kCheckpointMagic, 8) == 0;
}

Film readCheckpoint(const std::string& path, const CheckpointInfo& expected, int width, int height) {
  // A regular file only (a FIFO would block, /dev/zero never end), its size checked against the
  // header before the payload is read.
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0)
    throwInputError(path, "--resume", std::string("cannot open the checkpoint: ") + std::strerror(errno));
  if (S_ISDIR(st.st_mode)) throwInputError(path, "--resume", "is a directory, not a checkpoint");
  if (!S_ISREG(st.st_mode)) throwInputError(path, "--resume", "not a regular file, not a checkpoint");
  std::ifstream in(path, std::ios::binary);
  if (!in) throwInputError(path, "--resume", std::string("cannot open the checkpoint: ") + std::strerror(errno));
  Header h{};
  if (std::uint64_t(st.st_size) < sizeof h || !in.read(reinterpret_cast<char*>(&h), sizeof h))
    throwInputError(path, "--resume", "not a montecl checkpoint (too short)");
  if (std::memcmp(h.magic, kCheckpointMagic, 8) != 0) throwInputError(path, "--resume", "not a montecl checkpoint");
  if (h.version != kVersion || h.headerBytes != sizeof h)
    throwInputError(path, "--resume", "checkpoint version " + std::to_string(h.version) + ", expected " +
                                           std::to_string(kVersion));
  const auto refuse = [&](const std::string& what) {
    throwInputError(path, "--resume", "checkpoint of another render (" + what + "): refusing to resume");
  };
  if (int(h.width) != width || int(h.height) != height)
    refuse(std::to_string(h.width) + "x" + std::to_string(h.height) + " image, this render is " +
           std::to_string(width) + "x" + std::to_string(height));
  if (h.seed != expected.seed) refuse("seed " + std::to_string(h.seed) + ", this render's is " + std::to_string(expected.seed));
  if (h.spp != expected.spp) refuse("spp " + std::to_string(h.spp) + ", this render's is " + std::to_string(expected.spp));
  if (h.firstSample != expected.firstSample) refuse("first sample " + std::to_string(h.firstSample));
  if (bool(h.aovs) != expected.aovs) refuse(h.aovs ? "with AOVs" : "without AOVs");
  // Before the emission AOV the field was 1 and the film held 2 AOV vectors per pixel.
  if (h.aovs && h.aovs != MCL_AOV_VECTORS)
    refuse(std::to_string(h.aovs == 1 ? 2 : h.aovs) + " AOV vectors per pixel, this montecl writes " +
           std::to_string(MCL_AOV_VECTORS) + ": from an older montecl");
  if (h.key != expected.key) refuse("other scene or settings: key " + hex64(h.key) + ", this render's is " + hex64(expected.key));
  Film film;
  film.width = width;
  film.height = height;
  const std::size_t n = std::size_t(width) * height;
  if (h.splits > 64) throwInputError(path, "--resume", "damaged checkpoint (" + std::to_string(h.splits) + " sub-sequences)");
  const std::size_t need = sizeof h + n * (4 * 16 + 8) + (h.aovs ? MCL_AOV_VECTORS * n * 16 : 0) + std::size_t(h.splits) * n * 16 +
                           (expected.adaptive ? n * 8 : 0);
  if (std::uint64_t(st.st_size) != need) throwInputError(path, "--resume", "damaged checkpoint (wrong size)");
  std::string payload(need - sizeof h, '\0');
  if (!in.read(payload.data(), std::streamsize(payload.size())))
    throwInputError(path, "--resume", "damaged checkpoint (shorter than its size)");
  if (fnv1a64(payload) != h.payloadHash) throwInputError(path, "--resume", "damaged checkpoint (payload hash)");
  const char* at = payload.data();
  const auto take = [&](auto& v, std::size_t count) {
    v.resize(count);
    std::memcpy(v.data(), at, count * sizeof(v[0]));
    at += count * sizeof(v[0]);
  };
  take(film.mean, n);
  take(film.meanLo, n);
  take(film.m2, n);
  take(film.m2Lo, n);
  take(film.count, n);
  if (h.aovs) take(film.aovSum, MCL_AOV_VECTORS * n);
  if (h.splits) take(film.split, std::size_t(h.splits) * n);
  if (expected.adaptive) take(film.roundTarget, n);
  return film;
}

}  // namespace montecl
