// pbrt_scene.cpp: the pbrt-v4 directive reader (pbrt_scene.h): reads a .pbrt file and its
// Includes token by token, keeps pbrt's graphics state (the CTM, attribute and transform blocks,
// the current material, area light and orientation, named coordinate systems, materials,
// textures and objects), and writes a montecl Scene. The directives' pieces are read by
// pbrt_camera, pbrt_options, pbrt_shapes, pbrt_materials and pbrt_lights.
#include "scene/pbrt_scene.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <tuple>

#include "scene/load_util.h"
#include "scene/mesh_entry.h"
#include "scene/pbrt_camera.h"
#include "scene/pbrt_input.h"
#include "scene/pbrt_lights.h"
#include "scene/pbrt_materials.h"
#include "scene/pbrt_options.h"
#include "scene/pbrt_params.h"
#include "scene/pbrt_shapes.h"
#include "scene/pbrt_tokenizer.h"
#include "scene/pbrt_transforms.h"
#include "scene/scene_instances.h"
#include "scene/scene_readers.h"
#include "util/errors.h"

namespace montecl {
namespace {

struct AreaLight {
  bool on = false;
  glm::vec3 L{0.0f};
  bool twoSided = false;
};

struct GraphicsState {
  glm::dmat4 ctm{1.0};
  bool reverseOrientation = false;
  int material = 0;  // index into Reader::materials_
  AreaLight area;
  PbrtLoc loc;                 // where the block began (for a missing End)
  bool transformOnly = false;  // TransformBegin: only the CTM is restored
};

struct ObjectDef {
  std::vector<SceneTriangle> triangles;  // object space
  std::vector<glm::dmat4> placements;
};

class Reader {
 public:
  Reader(const std::string& path, std::vector<std::string>& warnings) : main_(path), warnings_(warnings) {
    scene_.path = path;
    scene_.inputFiles.push_back(path);
    scene_.render.integrator = Integrator::Path;  // pbrt-v4's default integrator: volpath, maxdepth 5
    scene_.render.maxDepth = 5 + 1;
    scene_.render.spp = 16;  // pbrt-v4's default pixelsamples
    MaterialDesc grey;       // pbrt-v4's default material: diffuse, reflectance 0.5
    grey.name = "pbrt default";
    materials_.push_back(grey);
  }

  Scene read() {
    in_.open(main_, PbrtLoc{main_, 0, 0}, scene_.inputFiles);
    while (!in_.empty()) {
      PbrtToken t = in_.tok().next();
      if (t.kind == PbrtToken::End) {
        in_.close();
        continue;
      }
      if (t.kind != PbrtToken::Word) pbrtFail(t.loc, "expected a directive, got '" + oneLine(t.text, 40) + "'");
      directive(t);
    }
    if (!stack_.empty()) pbrtFail(stack_.back().loc, "this block is never closed (AttributeEnd / TransformEnd missing)");
    if (inObject_) pbrtFail(objectLoc_, "ObjectBegin without ObjectEnd");
    if (!worldBegun_) pbrtFail(PbrtLoc{main_, 1, 1}, "no WorldBegin: the file describes no scene");
    finish();
    return std::move(scene_);
  }

 private:
  void warn(const PbrtLoc& loc, const std::string& text) { warnings_.push_back(loc.str() + ": " + text); }
  void unused(const PbrtParams& p, const std::string& what) { p.reportUnused(what, warnings_); }

  void optionsOnly(const PbrtToken& d) {
    if (worldBegun_) pbrtFail(d.loc, d.text + " is not allowed after WorldBegin");
  }
  void worldOnly(const PbrtToken& d) {
    if (!worldBegun_) pbrtFail(d.loc, d.text + " is not allowed before WorldBegin");
  }

  // ---- directives ----
  void directive(const PbrtToken& d) {
    const std::string& w = d.text;
    GraphicsState& g = state_;
    if (applyPbrtTransform(d, in_, g.ctm)) {
    } else if (w == "CoordinateSystem") {
      namedCoords_[in_.name(d)] = g.ctm;
    } else if (w == "CoordSysTransform") {
      const PbrtToken n = in_.expect(PbrtToken::String, "a coordinate system's name", d.loc);
      auto it = namedCoords_.find(n.text);
      if (it == namedCoords_.end()) warn(n.loc, "CoordSysTransform: coordinate system '" + oneLine(n.text, 40) + "' is not defined, ignored (as pbrt does)");
      else g.ctm = it->second;
    } else if (w == "ActiveTransform") {
      const PbrtToken which = in_.expect(PbrtToken::Word, "StartTime, EndTime or All", d.loc);
      if (which.text != "StartTime" && which.text != "EndTime" && which.text != "All") pbrtFail(which.loc, "ActiveTransform: expected StartTime, EndTime or All");
      if (which.text != "All" && !motionWarned_) {
        motionWarned_ = true;
        warn(d.loc, "ActiveTransform: montecl renders no motion blur; every transform applies at once (the end times' too)");
      }
    } else if (w == "TransformTimes") {
      in_.numbers(d, 2);
    } else if (w == "ReverseOrientation") {
      g.reverseOrientation = !g.reverseOrientation;
    } else if (w == "AttributeBegin" || w == "TransformBegin") {
      GraphicsState saved = g;
      saved.loc = d.loc;
      saved.transformOnly = w == "TransformBegin";
      stack_.push_back(saved);
    } else if (w == "AttributeEnd" || w == "TransformEnd") {
      if (stack_.empty()) pbrtFail(d.loc, w + " without a matching " + (w == "AttributeEnd" ? "AttributeBegin" : "TransformBegin"));
      const bool transformOnly = w == "TransformEnd";
      if (stack_.back().transformOnly != transformOnly)
        pbrtFail(d.loc, w + " closes the " + (transformOnly ? "AttributeBegin" : "TransformBegin") + " of " + stack_.back().loc.str());
      if (transformOnly) g.ctm = stack_.back().ctm;
      else g = stack_.back();
      stack_.pop_back();
    } else if (w == "Attribute") {
      in_.name(d);
      const PbrtParams p = in_.params(d);
      warn(d.loc, "Attribute: default parameters for a category are not read by montecl, ignored");
      for (const PbrtParam& q : p.list) q.used = true;
    } else if (w == "Include" || w == "Import") {
      const PbrtToken n = in_.expect(PbrtToken::String, "a file name", d.loc);
      in_.open(besideFile(main_, n.text), n.loc, scene_.inputFiles);
    } else if (w == "Option") {
      const PbrtParams p = in_.params(d);  // Option "bool disablepixeljitter" true: one parameter
      if (p.list.empty()) pbrtFail(d.loc, "Option: expected a parameter \"type name\" value");
      for (const PbrtParam& q : p.list) warn(q.loc, "Option '" + oneLine(q.name, 60) + "' not read by montecl, ignored");
    } else if (w == "ColorSpace") {
      const PbrtToken n = in_.expect(PbrtToken::String, "a colour space", d.loc);
      if (n.text != "srgb") warn(n.loc, "ColorSpace '" + oneLine(n.text, 40) + "': montecl renders in linear sRGB; RGB values are read as sRGB");
    } else if (w == "Camera") {
      optionsOnly(d);
      cameraType_ = in_.name(d);
      cameraParams_ = in_.params(d);
      cameraFromWorld_ = g.ctm;
      cameraSet_ = true;
      // pbrt names the camera's space "camera" (camera-to-world).
      namedCoords_["camera"] = glm::inverse(g.ctm);
    } else if (w == "Film") {
      optionsOnly(d);
      const std::string type = in_.name(d);  // before the parameters (argument order is unspecified)
      pbrtFilm(type, in_.params(d), width_, height_, warnings_);
    } else if (w == "Sampler") {
      optionsOnly(d);
      const std::string type = in_.name(d);  // before the parameters (argument order is unspecified)
      pbrtSampler(type, in_.params(d), scene_.render, warnings_);
    } else if (w == "Integrator") {
      optionsOnly(d);
      const std::string type = in_.name(d);  // before the parameters (argument order is unspecified)
      pbrtIntegrator(type, in_.params(d), scene_.render, warnings_);
    } else if (w == "PixelFilter") {
      optionsOnly(d);
      const std::string type = in_.name(d);  // before the parameters (argument order is unspecified)
      pbrtPixelFilter(type, in_.params(d), scene_.render, warnings_);
    } else if (w == "Accelerator") {
      optionsOnly(d);
      in_.name(d);
      const PbrtParams p = in_.params(d);
      for (const PbrtParam& q : p.list) q.used = true;  // montecl builds its own BVH
    } else if (w == "MakeNamedMedium") {
      in_.name(d);
      const PbrtParams p = in_.params(d);
      for (const PbrtParam& q : p.list) q.used = true;
      warn(d.loc, "MakeNamedMedium: montecl renders no participating media; the medium is left out");
    } else if (w == "MediumInterface" || w == "CameraMedium") {
      in_.expect(PbrtToken::String, "a medium's name", d.loc);
      if (w == "MediumInterface" && in_.tok().peek().kind == PbrtToken::String) in_.tok().next();
      if (!mediaWarned_) {
        mediaWarned_ = true;
        warn(d.loc, w + ": montecl renders no participating media; media are left out");
      }
    } else if (w == "WorldBegin") {
      optionsOnly(d);
      worldBegin(d);
    } else if (w == "WorldEnd") {
      warn(d.loc, "WorldEnd is pbrt-v3's; pbrt-v4 ends the scene at the end of the file, ignored");
    } else if (w == "MakeNamedMaterial") {
      worldOnly(d);
      const PbrtToken n = in_.expect(PbrtToken::String, "a material's name", d.loc);
      const PbrtParams p = in_.params(d);
      const std::string type = p.getString("type", "");
      if (!p.find("type")) pbrtFail(d.loc, "MakeNamedMaterial '" + oneLine(n.text, 40) + "': 'string type' is required");
      if (namedMaterials_.count(n.text)) warn(n.loc, "MakeNamedMaterial: '" + oneLine(n.text, 40) + "' redefined; the new one is used from here on");
      MaterialDesc m = pbrtMaterial(type, p, textures_, namedMaterialDescs_, main_, warnings_);
      m.name = n.text;
      unused(p, "MakeNamedMaterial '" + oneLine(n.text, 40) + "'");
      namedMaterialDescs_[n.text] = m;
      materials_.push_back(m);
      namedMaterials_[n.text] = int(materials_.size()) - 1;
    } else if (w == "NamedMaterial") {
      worldOnly(d);
      const PbrtToken n = in_.expect(PbrtToken::String, "a material's name", d.loc);
      auto it = namedMaterials_.find(n.text);
      if (it == namedMaterials_.end()) pbrtFail(n.loc, "NamedMaterial: material '" + oneLine(n.text, 60) + "' is not defined");
      g.material = it->second;
    } else if (w == "Material") {
      worldOnly(d);
      const std::string type = in_.name(d);
      const PbrtParams p = in_.params(d);
      MaterialDesc m = pbrtMaterial(type, p, textures_, namedMaterialDescs_, main_, warnings_);
      m.name = type + " (" + d.loc.str() + ")";
      unused(p, "Material \"" + oneLine(type, 40) + "\"");
      materials_.push_back(m);
      g.material = int(materials_.size()) - 1;
    } else if (w == "Texture") {
      worldOnly(d);
      const PbrtToken n = in_.expect(PbrtToken::String, "a texture's name", d.loc);
      const PbrtToken kind = in_.expect(PbrtToken::String, "\"spectrum\" or \"float\"", d.loc);
      if (kind.text != "spectrum" && kind.text != "float" && kind.text != "color")
        pbrtFail(kind.loc, "Texture: expected \"spectrum\" or \"float\", got \"" + oneLine(kind.text, 40) + "\"");
      const std::string klass = in_.name(d);
      const PbrtParams p = in_.params(d);
      PbrtTexture t = pbrtTexture(klass, p, textures_, main_, warnings_);
      if (!t.file.empty()) notePbrtTextureFile(scene_, t, p);
      unused(p, "Texture '" + oneLine(n.text, 40) + "'");
      textures_[n.text] = t;
    } else if (w == "AreaLightSource") {
      worldOnly(d);
      const std::string type = in_.name(d);
      const PbrtParams p = in_.params(d);
      if (type != "diffuse") {
        warn(d.loc, "AreaLightSource \"" + oneLine(type, 40) + "\" not read by montecl (it reads \"diffuse\"); the shapes do not emit");
        for (const PbrtParam& q : p.list) q.used = true;
        g.area = AreaLight{};
        return;
      }
      AreaLight a;
      a.on = true;
      a.L = glm::vec3(1.0f);
      pbrtLightSpectrum(p, "L", a.L, warnings_);
      a.L *= float(p.getFloat("scale", 1.0));
      a.twoSided = p.getBool("twosided", false);
      if (!(a.L.x >= 0.0f && a.L.y >= 0.0f && a.L.z >= 0.0f && std::isfinite(a.L.x + a.L.y + a.L.z)))
        pbrtFail(d.loc, "AreaLightSource: L x scale must be finite and >= 0");
      if (!p.getString("filename", "").empty()) warn(d.loc, "AreaLightSource: an image of emission ('filename') is not read by montecl; L is used");
      unused(p, "AreaLightSource \"diffuse\"");
      g.area = a;
    } else if (w == "LightSource") {
      worldOnly(d);
      const std::string type = in_.name(d);
      const PbrtParams p = in_.params(d);
      pbrtLightSource(type, p, mirror_ * g.ctm, main_, scene_, warnings_);
      unused(p, "LightSource \"" + oneLine(type, 40) + "\"");
    } else if (w == "Shape") {
      worldOnly(d);
      shape(d);
    } else if (w == "ObjectBegin") {
      worldOnly(d);
      const PbrtToken n = in_.expect(PbrtToken::String, "an object's name", d.loc);
      if (inObject_) pbrtFail(d.loc, "ObjectBegin inside the ObjectBegin of " + objectLoc_.str());
      GraphicsState saved = g;
      saved.loc = d.loc;
      stack_.push_back(saved);  // pbrt-v4's ObjectBegin opens an attribute block
      if (objects_.count(n.text)) warn(n.loc, "ObjectBegin: object '" + oneLine(n.text, 40) + "' redefined; its shapes are added to the first definition");
      inObject_ = true;
      objectName_ = n.text;
      objectLoc_ = d.loc;
      objects_[n.text];
    } else if (w == "ObjectEnd") {
      if (!inObject_) pbrtFail(d.loc, "ObjectEnd without ObjectBegin");
      inObject_ = false;
      if (stack_.empty()) pbrtFail(d.loc, "ObjectEnd: its ObjectBegin's attribute block was already closed");
      g = stack_.back();
      stack_.pop_back();
    } else if (w == "ObjectInstance") {
      worldOnly(d);
      const PbrtToken n = in_.expect(PbrtToken::String, "an object's name", d.loc);
      if (inObject_) pbrtFail(d.loc, "ObjectInstance inside an object definition (pbrt-v4 does not nest instances)");
      auto it = objects_.find(n.text);
      if (it == objects_.end()) pbrtFail(n.loc, "ObjectInstance: object '" + oneLine(n.text, 60) + "' is not defined");
      it->second.placements.push_back(mirror_ * g.ctm);
    } else {
      pbrtFail(d.loc, "unknown directive '" + oneLine(w, 40) + "'");
    }
  }

  void worldBegin(const PbrtToken& d) {
    worldBegun_ = true;
    PbrtParams none;
    none.loc = d.loc;
    const PbrtCamera cam = pbrtCamera(cameraSet_ ? cameraType_ : "perspective", cameraSet_ ? cameraParams_ : none,
                                      cameraFromWorld_, width_, height_, warnings_);
    if (cameraSet_) unused(cameraParams_, "Camera \"" + oneLine(cameraType_, 40) + "\"");
    scene_.camera = cam.camera;
    mirror_ = cam.worldMirror;
    // pbrt-v4 resets the CTM at WorldBegin and names it "world".
    state_.ctm = glm::dmat4(1.0);
    namedCoords_["world"] = state_.ctm;
  }

  // The scene material for the current state: the material, with the area light's emission and
  // the shape's alpha texture (by its texture name; "" for none).
  std::uint32_t materialFor(const GraphicsState& g, const std::string& alphaName) {
    const glm::vec3 L = g.area.on ? g.area.L : glm::vec3(0.0f);
    const bool twoSided = g.area.on && g.area.twoSided;
    const auto key = std::make_tuple(g.material, L.x, L.y, L.z, twoSided, alphaName);
    auto it = materialIndex_.find(key);
    if (it != materialIndex_.end()) return it->second;
    MaterialDesc m = materials_[std::size_t(g.material)];
    m.emission = L;
    m.twoSidedEmission = twoSided;
    if (g.area.on) m.name += " (emitting)";
    if (!alphaName.empty()) {
      const PbrtTexture& t = textures_.at(alphaName);
      m.alphaTexture = t.file;
      m.alphaSampling = t.sampling;
      m.name += " (alpha '" + alphaName + "')";
    }
    scene_.materials.push_back(m);
    const std::uint32_t index = std::uint32_t(scene_.materials.size() - 1);
    materialIndex_[key] = index;
    return index;
  }

  // The shape's "alpha": "" (opaque), the name of an image texture cutting it out, or nullopt
  // when it is not there at all (alpha 0).
  std::optional<std::string> alphaOf(const PbrtParams& p) {
    const PbrtParam* a = p.find("alpha");
    if (!a) return std::string();
    double value = 1.0;
    if (a->type == "texture") {
      if (a->strings.size() != 1) pbrtFail(a->loc, "'texture alpha' must name one texture");
      auto it = textures_.find(a->strings[0]);
      if (it == textures_.end()) pbrtFail(a->loc, "texture '" + oneLine(a->strings[0], 60) + "' is not defined");
      if (!it->second.file.empty()) {
        if (it->second.value.x != 1.0f) warn(a->loc, "Shape: the alpha texture's scale is not read by montecl; its image alone cuts out");
        return it->first;  // montecl cuts out where the image's alpha channel (else its first) is below 0.5
      }
      value = it->second.value.x;
    } else if (a->type == "float" && a->numbers.size() == 1) {
      value = a->numbers[0];
    } else {
      pbrtFail(a->loc, "'alpha' must be a float or a texture, got " + a->type);
    }
    if (value <= 0.0) return std::nullopt;
    if (value < 1.0) warn(a->loc, "Shape: a constant alpha between 0 and 1 is not read by montecl; the shape is opaque");
    return std::string();
  }

  void shape(const PbrtToken& d) {
    const std::string type = in_.name(d);
    const PbrtParams p = in_.params(d);
    std::vector<SceneTriangle> tris;
    std::vector<std::string> plys;
    const bool read = pbrtShapeTriangles(type, p, main_, tris, warnings_, plys);
    for (const std::string& f : plys) scene_.inputFiles.push_back(f);
    const std::optional<std::string> alpha = alphaOf(p);
    for (const char* quiet : {"emissionfilename", "faceIndices"}) p.ignore(quiet);
    if (read) unused(p, "Shape \"" + oneLine(type, 40) + "\"");
    if (!read || tris.empty() || !alpha) return;  // alpha 0: pbrt leaves the shape out
    GraphicsState g = state_;
    if (inObject_) {
      if (g.area.on && !instanceLightWarned_) {
        instanceLightWarned_ = true;
        warn(d.loc, "Shape: area lights inside ObjectBegin are not emitters (pbrt-v4 does not support them either); the shape is not emitting");
      }
      g.area.on = false;
      placePbrtTriangles(tris, g.ctm, g.reverseOrientation);
      const std::uint32_t m = materialFor(g, *alpha);
      ObjectDef& o = objects_[objectName_];
      for (SceneTriangle& t : tris) t.material = m, o.triangles.push_back(t);
      return;
    }
    placePbrtTriangles(tris, mirror_ * g.ctm, g.reverseOrientation);
    const std::uint32_t m = materialFor(g, *alpha);
    for (SceneTriangle& t : tris) {
      t.material = m;
      appendTriangle(scene_, t);
    }
  }

  void finish() {
    // Instanced objects: their triangles after the world's, one mesh range each, placed per
    // ObjectInstance (montecl's two-level BVH).
    for (auto& [objName, o] : objects_) {
      if (o.placements.empty() || o.triangles.empty()) continue;
      MeshRange r;
      r.firstTri = std::uint32_t(scene_.triangles.size());
      for (const SceneTriangle& t : o.triangles) appendTriangle(scene_, t);
      r.count = std::uint32_t(scene_.triangles.size()) - r.firstTri;
      if (r.count == 0) continue;
      scene_.meshRanges.push_back(r);
      if (const std::string bad = addPlacements(scene_, std::uint32_t(scene_.meshRanges.size() - 1), o.placements);
          !bad.empty())
        pbrtFail(PbrtLoc{main_, 1, 1}, "ObjectInstance \"" + oneLine(objName, 40) + "\": a placement " + bad);
    }
    if (scene_.triangles.empty()) pbrtFail(PbrtLoc{main_, 1, 1}, "the scene has no triangles montecl can render");
    recomputeBounds(scene_);
  }

  std::string main_;
  std::vector<std::string>& warnings_;
  Scene scene_;
  PbrtInput in_;
  GraphicsState state_;
  std::vector<GraphicsState> stack_;
  std::map<std::string, glm::dmat4> namedCoords_;
  std::vector<MaterialDesc> materials_;  // every material defined ([0]: pbrt's default)
  std::map<std::string, int> namedMaterials_;
  std::map<std::string, MaterialDesc> namedMaterialDescs_;
  std::map<std::tuple<int, float, float, float, bool, std::string>, std::uint32_t> materialIndex_;
  PbrtTextures textures_;
  std::map<std::string, ObjectDef> objects_;
  bool inObject_ = false;
  std::string objectName_;
  PbrtLoc objectLoc_;
  bool worldBegun_ = false, cameraSet_ = false, motionWarned_ = false, mediaWarned_ = false, instanceLightWarned_ = false;
  std::string cameraType_;
  PbrtParams cameraParams_;
  glm::dmat4 cameraFromWorld_{1.0};
  int width_ = 1280, height_ = 720;  // pbrt-v4's default film
  glm::dmat4 mirror_{1.0};
};

}  // namespace

bool isPbrtScenePath(const std::string& path) { return lowerExtension(path) == ".pbrt"; }

Scene loadPbrtScene(const std::string& path, std::vector<std::string>& warnings, std::optional<MissingTextures> missing) {
  Reader reader(path, warnings);
  Scene scene = reader.read();
  settleMissingTextures(scene, missing, warnings);
  return scene;
}

}  // namespace montecl
