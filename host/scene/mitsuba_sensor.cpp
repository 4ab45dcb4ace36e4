// mitsuba_sensor.cpp: Mitsuba's sensor, film, sampler and integrator as montecl's camera and
// render settings (mitsuba_sensor.h).
#include "scene/mitsuba_sensor.h"

#include <algorithm>
#include <cmath>

#include "scene/camera_basis.h"
#include "scene/load_util.h"
#include "scene/mitsuba_transform.h"

namespace montecl {
namespace {

// Mitsuba's reconstruction filters as montecl's pixel filter (importance sampled, so each sample
// keeps weight 1 where Mitsuba splats weighted samples: the same expected pixel for filters >= 0).
// Its parameters: gaussian stddev (radius 4 stddev), tent radius, mitchell / catmullrom B and C
// (radius 2), lanczos lobes (the radius and the window).
void rfilter(MiContext& c, const MiProps& rf, RenderSettings& r) {
  PixelFilter f;
  std::vector<std::pair<const char*, double>> params;
  if (rf.type == "box") {
    defaultFilter("box", f);
    params = {{"radius", rf.getFloat("radius", 0.5)}};
  } else if (rf.type == "tent") {
    defaultFilter("triangle", f);
    params = {{"radius", rf.getFloat("radius", 1.0)}};
  } else if (rf.type == "gaussian") {
    defaultFilter("gaussian", f);
    const double sd = rf.getFloat("stddev", 0.5);
    params = {{"radius", 4.0 * sd}, {"sigma", sd}};
  } else if (rf.type == "mitchell" || rf.type == "catmullrom") {
    defaultFilter("mitchell", f);
    const bool cr = rf.type == "catmullrom";
    params = {{"radius", 2.0}, {"b", rf.getFloat("B", cr ? 0.0 : 1.0 / 3.0)}, {"c", rf.getFloat("C", cr ? 0.5 : 1.0 / 3.0)}};
  } else if (rf.type == "lanczos") {
    defaultFilter("lanczos", f);
    const int lobes = rf.getInt("lobes", 3);
    params = {{"radius", double(lobes)}, {"tau", double(lobes)}};
  } else {
    c.warn(rf.loc, "rfilter \"" + oneLine(rf.type, 40) + "\": unknown to montecl; a box of radius 0.5 is used");
    return;
  }
  std::string problem;
  for (const auto& q : params)
    if (!setFilterParam(f, q.first, float(q.second), &problem))
      mitsubaFail(rf.loc, "rfilter \"" + oneLine(rf.type, 40) + "\": " + problem);
  r.filter = f;
  rf.reportUnused("rfilter \"" + rf.type + "\"", c.warnings);
}

void film(MiContext& c, const MiProps& sensor, Camera& cam) {
  const std::vector<MiElem> films = sensor.objects("film");
  if (films.empty()) return;
  const MiProps p(c.doc, films[0]);
  if (p.type != "hdrfilm" && p.type != "specfilm")
    c.warn(p.loc, "film \"" + oneLine(p.type, 40) + "\": read as hdrfilm (width, height)");
  cam.width = p.getInt("width", 768);
  cam.height = p.getInt("height", 576);
  if (cam.width < 1 || cam.height < 1) mitsubaFail(p.loc, "film: 'width' and 'height' must be >= 1");
  for (const char* quiet : {"pixel_format", "component_format", "file_format", "banner", "high_quality_edges",
                            "sample_border", "compensate", "rgb", "channels"})
    p.find(quiet);  // how Mitsuba stores its image: montecl's output is the command line's -o
  if (p.find("crop_width") || p.find("crop_height") || p.find("crop_offset_x") || p.find("crop_offset_y"))
    c.warn(p.loc, "film: a crop window is not read by montecl; the whole image is rendered");
  for (const MiElem& f : p.objects("rfilter")) rfilter(c, MiProps(c.doc, f), c.scene.render);
  p.reportUnused("film \"" + p.type + "\"", c.warnings);
}

void sampler(MiContext& c, const MiProps& sensor, RenderSettings& r) {
  const std::vector<MiElem> samplers = sensor.objects("sampler");
  if (samplers.empty()) return;
  const MiProps p(c.doc, samplers[0]);
  r.spp = p.getInt("sample_count", 4);
  if (r.spp < 1) mitsubaFail(p.locOf("sample_count"), "sampler: 'sample_count' must be >= 1");
  // montecl has two samplers: independent numbers, or its stratified Owen-scrambled Sobol points
  // for every stratified kind Mitsuba has (stratified, multijitter, orthogonal, ldsampler, ...).
  r.sampler = p.type == "independent" ? Sampler::Independent : Sampler::Sobol;
  const int seed = p.getInt("seed", 0);
  if (seed < 0) mitsubaFail(p.locOf("seed"), "sampler: 'seed' must be >= 0");
  r.seed = std::uint32_t(seed);
  p.find("jitter");
  p.find("scramble_seed");
  p.reportUnused("sampler \"" + p.type + "\"", c.warnings);
}

// The vertical field of view of a fov along Mitsuba's fov_axis for a w x h image.
double verticalFov(const MiProps& p, double fov, const std::string& axis, int w, int h) {
  const double t = std::tan(glm::radians(fov) * 0.5);
  double scale = 1.0;  // tan(fov_y / 2) = t * scale
  if (axis == "x" || (axis == "smaller" && w <= h) || (axis == "larger" && w >= h)) scale = double(h) / double(w);
  else if (axis == "diagonal") scale = double(h) / std::sqrt(double(w) * w + double(h) * h);
  else if (axis != "y" && axis != "smaller" && axis != "larger")
    mitsubaFail(p.locOf("fov_axis"), "sensor: fov_axis must be x, y, diagonal, smaller or larger, got '" + oneLine(axis, 20) + "'");
  return glm::degrees(2.0 * std::atan(t * scale));
}

}  // namespace

MiCamera miSensor(MiContext& c, const MiElem* sensorElem) {
  MiCamera out;
  Camera& cam = out.camera;
  cam.width = 768, cam.height = 576;  // Mitsuba's hdrfilm
  cam.position = glm::vec3(0.0f), cam.target = glm::vec3(0, 0, 1), cam.up = glm::vec3(0, 1, 0);
  if (!sensorElem) {
    cam.fovY = float(glm::degrees(2.0 * std::atan(std::tan(glm::radians(39.3077) * 0.5) * 576.0 / 768.0)));
    return out;  // Mitsuba's image right is -x, montecl's cross(+z, +y) = -x: they agree
  }
  const MiProps p(c.doc, *sensorElem);
  if (p.type != "perspective" && p.type != "thinlens")
    c.warn(p.loc, "sensor \"" + oneLine(p.type, 40) + "\": montecl has the perspective camera and a thin lens; rendered as perspective");
  film(c, p, cam);
  sampler(c, p, c.scene.render);
  double fov = 39.3077;  // Mitsuba's default, a 50 mm lens on 35 mm film along x
  std::string axis = p.getString("fov_axis", "x");
  if (p.find("fov")) {
    fov = p.getFloat("fov", fov);
  } else if (p.find("focal_length")) {
    const std::string f = p.getString("focal_length", "50mm");
    const double mm = std::atof(f.c_str());
    if (!(mm > 0.0)) mitsubaFail(p.locOf("focal_length"), "sensor: 'focal_length' must be a length such as 50mm");
    fov = glm::degrees(2.0 * std::atan(std::sqrt(36.0 * 36.0 + 24.0 * 24.0) / (2.0 * mm)));
    axis = "diagonal";
    c.warn(p.locOf("focal_length"), "sensor: focal_length read as the 35 mm film equivalent over the image diagonal");
  }
  if (!(fov > 0.0 && fov < 180.0)) mitsubaFail(p.locOf("fov"), "sensor: 'fov' must be in (0, 180) degrees");
  cam.fovY = float(axis == "y" ? fov : verticalFov(p, fov, axis, cam.width, cam.height));
  if (p.type == "thinlens") {
    cam.apertureRadius = float(p.getFloat("aperture_radius", 0.0));
    cam.focusDistance = float(p.getFloat("focus_distance", 0.0));
    if (!(cam.apertureRadius >= 0.0f) || !(cam.focusDistance >= 0.0f))
      mitsubaFail(p.loc, "thinlens: 'aperture_radius' and 'focus_distance' must be >= 0");
  }
  for (const char* quiet : {"near_clip", "far_clip", "shutter_open", "shutter_close", "principal_point_offset_x",
                            "principal_point_offset_y"})
    p.find(quiet);
  const MiElem tw = p.find("to_world");
  MiLookAt look;
  const glm::dmat4 m = tw ? miTransform(c.doc, tw, &look) : glm::dmat4(1.0);
  const glm::dvec3 pos(m[3]), forward = glm::normalize(glm::dvec3(m[2])), up = glm::normalize(glm::dvec3(m[1]));
  if (look.only) {  // as written, so that the camera is a scene file's camera with these points, bit for bit
    cam.position = glm::vec3(look.origin), cam.target = glm::vec3(look.target), cam.up = glm::vec3(look.up);
  } else {
    cam.position = glm::vec3(pos), cam.target = glm::vec3(pos + forward), cam.up = glm::vec3(up);
  }
  const CameraProblem problem = cameraBasisProblem(cam);
  if (!problem.empty()) mitsubaFail(p.loc, "sensor: 'to_world' gives an unusable camera (" + problem.key + " " + problem.problem + ")");
  // Mitsuba's image right is the camera's -x; montecl's is cross(forward, up). Where they differ
  // (a to_world that mirrors), the world is reflected through the camera's vertical plane.
  const glm::dvec3 right = glm::normalize(-glm::dvec3(m[0]));
  const glm::dvec3 monteclRight = glm::normalize(glm::cross(forward, up));
  if (glm::dot(right, monteclRight) < 0.0) {
    out.worldMirror = reflectionThroughPlane(monteclRight, pos);
    out.mirrored = true;
  }
  p.reportUnused("sensor \"" + p.type + "\"", c.warnings);
  return out;
}

void miIntegrator(MiContext& c, const MiElem& e, RenderSettings& r) {
  const MiProps p(c.doc, e);
  const std::string what = "integrator \"" + oneLine(p.type, 40) + "\"";
  r.integrator = p.type == "direct" ? Integrator::Direct : Integrator::Path;
  if (p.type == "direct") {
    const int shading = p.getInt("shading_samples", 1);
    const int em = p.getInt("emitter_samples", shading), bs = p.getInt("bsdf_samples", shading);
    if (em < 0 || bs < 0 || em + bs == 0) mitsubaFail(p.loc, "direct: 'emitter_samples' and 'bsdf_samples' must be >= 0, not both 0");
    if (em > 1024) mitsubaFail(p.locOf("emitter_samples"), "direct: montecl takes at most 1024 emitter samples");
    r.directSampling = bs == 0 ? DirectSampling::Light : em == 0 ? DirectSampling::Brdf : DirectSampling::Mis;
    r.lightSamples = std::max(em, 1);
    if (bs > 1) c.warn(p.locOf("bsdf_samples"), "direct: montecl draws one BSDF sample per shading point; bsdf_samples " + std::to_string(bs) + " read as 1");
  } else {
    if (p.type != "path")
      c.warn(p.loc, what + ": montecl renders it with its path tracer (next-event estimation, MIS), same depth" +
                        std::string(p.type.rfind("vol", 0) == 0 ? "; no participating media" : ""));
    // Mitsuba's max_depth counts path segments (1: emitters seen, 2: direct light): montecl's convention.
    r.maxDepth = p.getInt("max_depth", -1);
    if (r.maxDepth == 0 || r.maxDepth < -1) mitsubaFail(p.locOf("max_depth"), "path: max_depth must be -1 (unlimited) or >= 1 for montecl");
    r.rrDepth = p.getInt("rr_depth", 5);
    if (r.rrDepth < 1) mitsubaFail(p.locOf("rr_depth"), "path: rr_depth must be >= 1");
  }
  if (p.getBool("hide_emitters", false)) c.warn(p.locOf("hide_emitters"), what + ": hide_emitters is not read by montecl; emitters are seen");
  p.find("samples_per_pass");
  p.find("timeout");
  for (const MiElem& nestedIntegrator : p.objects("integrator"))
    c.warn(c.doc.loc(nestedIntegrator), what + ": its nested integrator is not read; montecl's path tracer is used");
  p.reportUnused(what, c.warnings);
}

}  // namespace montecl
