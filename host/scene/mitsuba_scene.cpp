// mitsuba_scene.cpp: the Mitsuba 3 scene reader (mitsuba_scene.h): walks the scene's elements in
// order (shapes with their BSDF and area emitter, emitters, the sensor, the integrator) and writes
// a montecl Scene. The elements' pieces are read by mitsuba_sensor, mitsuba_shapes, mitsuba_bsdfs,
// mitsuba_textures and mitsuba_emitters.
#include "scene/mitsuba_scene.h"

#include <map>
#include <tuple>
#include <utility>

#include "scene/load_util.h"
#include "scene/mesh_entry.h"
#include "scene/mitsuba_bsdfs.h"
#include "scene/mitsuba_emitters.h"
#include "scene/mitsuba_sensor.h"
#include "scene/mitsuba_shapes.h"
#include "scene/scene_readers.h"
#include "util/errors.h"

namespace montecl {
namespace {

class Reader {
 public:
  Reader(const std::string& path, std::vector<std::string>& warnings)
      : doc_(path, scene_.inputFiles), c_{doc_, scene_, warnings} {
    scene_.path = path;
    // Mitsuba's defaults: the path tracer (unlimited depth, roulette from depth 5), 4 independent samples.
    scene_.render.integrator = Integrator::Path;
    scene_.render.maxDepth = -1;
    scene_.render.rrDepth = 5;
    scene_.render.spp = 4;
    scene_.render.sampler = Sampler::Independent;
  }

  Scene read() {
    MiElem sensor;
    for (const MiElem& e : doc_.sceneChildren()) {
      const std::string t = e.tag();
      if (t == "shape") {
        shape(e);
      } else if (t == "emitter") {
        miEmitter(c_, e);
      } else if (t == "sensor") {
        if (sensor) c_.warn(doc_.loc(e), "montecl renders one sensor; this one is left out (the first is used)");
        else sensor = e;
      } else if (t == "integrator") {
        miIntegrator(c_, e, scene_.render);
      } else if (t == "bsdf" || t == "texture") {
        // definitions read where a <ref> names them
      } else if (t == "medium" || t == "phase" || t == "volume") {
        c_.warn(doc_.loc(e), "<" + t + ">: montecl renders no participating media, left out");
      } else {
        c_.warn(doc_.loc(e), "<" + oneLine(t, 40) + "> not read by montecl, left out");
      }
    }
    const MiCamera cam = miSensor(c_, sensor ? &sensor : nullptr);
    scene_.camera = cam.camera;
    if (cam.mirrored) mirror(cam.worldMirror);
    if (scene_.triangles.empty()) mitsubaFail(MiLoc{doc_.mainPath(), 1, 1}, "the scene has no shape montecl can render");
    recomputeBounds(scene_);
    return std::move(scene_);
  }

 private:
  // The material of a BSDF element, read once however many shapes name it.
  const MiMaterial& bsdf(const MiElem& e) {
    const auto key = std::make_pair(e.file, e.node.internal_object());
    auto it = bsdfs_.find(key);
    if (it == bsdfs_.end()) it = bsdfs_.emplace(key, miBsdf(c_, e)).first;
    return it->second;
  }

  std::uint32_t materialFor(const MiMaterial& m, const MiAreaLight* light) {
    MaterialDesc d = m.desc;
    if (light) {
      d.emission = light->radiance;
      d.emissionTexture = light->texture;
      d.emissionSampling = light->sampling;
    }
    const auto key = std::make_tuple(&m, d.emission.x, d.emission.y, d.emission.z, d.emissionTexture);
    auto it = materialIndex_.find(key);
    if (it != materialIndex_.end()) return it->second;
    const std::uint32_t index = std::uint32_t(scene_.materials.size());
    scene_.materials.push_back(d);
    materialIndex_.emplace(key, index);
    return index;
  }

  void shape(const MiElem& e) {
    const MiProps p(doc_, e);
    std::vector<SceneTriangle> tris;
    if (!miShapeTriangles(c_, p, tris)) return;
    const std::vector<MiElem> bsdfs = p.objects("bsdf");
    const std::vector<MiElem> emitters = p.objects("emitter");
    if (bsdfs.size() > 1) c_.warn(doc_.loc(bsdfs[1]), "shape: one BSDF per shape; the first is used");
    const MiMaterial& m = bsdfs.empty() ? defaultMaterial_ : bsdf(bsdfs[0]);
    if (!m.twoSided && !oneSidedWarned_ && m.desc.kind != MCL_MATERIAL_dielectric &&
        m.desc.kind != MCL_MATERIAL_thin_dielectric) {
      oneSidedWarned_ = true;
      c_.warn(p.loc, "shape: its BSDF is one-sided in Mitsuba (black from behind) and two-sided in montecl; wrap it in \"twosided\" for the same picture");
    }
    MiAreaLight light;
    if (!emitters.empty()) light = miAreaEmitter(c_, emitters[0]);
    if (emitters.size() > 1) c_.warn(doc_.loc(emitters[1]), "shape: one emitter per shape; the first is used");
    p.reportUnused("shape \"" + p.type + "\"", c_.warnings);
    if (m.invisible) return;  // a mask of opacity 0
    const std::uint32_t index = materialFor(m, emitters.empty() ? nullptr : &light);
    for (SceneTriangle& t : tris) {
      t.material = index;
      appendTriangle(scene_, t);
    }
  }

  // Reflects every triangle and light through the camera's vertical plane (mitsuba_sensor.h);
  // two corners swap so that each front stays the reflected front.
  void mirror(const glm::dmat4& s) {
    const glm::dmat3 lin(s);
    for (SceneTriangle& t : scene_.triangles) {
      for (int k = 0; k < 3; ++k) {
        t.v[k] = glm::vec3(s * glm::dvec4(glm::dvec3(t.v[k]), 1.0));
        t.n[k] = glm::vec3(lin * glm::dvec3(t.n[k]));
      }
      std::swap(t.v[1], t.v[2]);
      std::swap(t.n[1], t.n[2]);
      std::swap(t.uv[1], t.uv[2]);
    }
    for (LightDesc& l : scene_.lights) {
      l.position = glm::vec3(s * glm::dvec4(glm::dvec3(l.position), 1.0));
      l.direction = glm::vec3(lin * glm::dvec3(l.direction));
    }
    if (scene_.environment.enabled && !scene_.environment.file.empty())
      c_.warn(MiLoc{doc_.mainPath(), 1, 1}, "the sensor's to_world mirrors the picture; montecl reflects the world to match, but not the environment map");
  }

  Scene scene_;
  MiDocument doc_;
  MiContext c_;
  MiMaterial defaultMaterial_;  // no BSDF: Mitsuba's diffuse of reflectance 0.5
  std::map<std::pair<int, const void*>, MiMaterial> bsdfs_;
  std::map<std::tuple<const MiMaterial*, float, float, float, std::string>, std::uint32_t> materialIndex_;
  bool oneSidedWarned_ = false;
};

}  // namespace

Scene loadMitsubaScene(const std::string& path, std::vector<std::string>& warnings, std::optional<MissingTextures> missing) {
  Reader reader(path, warnings);
  Scene scene = reader.read();
  settleMissingTextures(scene, missing, warnings);
  return scene;
}

}  // namespace montecl
