// pbrt_camera.cpp: pbrt-v4's camera as montecl's (pbrt_camera.h): reads the Camera directive's
// CTM and parameters, writes a Camera and the world's mirror.
#include "scene/pbrt_camera.h"

#include <cmath>

#include "scene/camera_basis.h"

namespace montecl {

PbrtCamera pbrtCamera(const std::string& type, const PbrtParams& params, const glm::dmat4& cameraFromWorld, int width,
                      int height, std::vector<std::string>& warnings) {
  if (type != "perspective")
    warnings.push_back(params.loc.str() + ": Camera \"" + type +
                       "\": montecl has only the perspective camera; rendered as perspective (fov 90 unless given)");
  if (std::abs(glm::determinant(cameraFromWorld)) < 1e-300)
    pbrtFail(params.loc, "the transformation at Camera is singular (no camera position or direction)");
  const glm::dmat4 toWorld = glm::inverse(cameraFromWorld);
  const glm::dvec3 pos = glm::dvec3(toWorld * glm::dvec4(0, 0, 0, 1));
  const glm::dvec3 forward = glm::normalize(glm::dvec3(toWorld * glm::dvec4(0, 0, 1, 0)));
  const glm::dvec3 up = glm::normalize(glm::dvec3(toWorld * glm::dvec4(0, 1, 0, 0)));
  const glm::dvec3 right = glm::normalize(glm::dvec3(toWorld * glm::dvec4(1, 0, 0, 0)));
  PbrtCamera out;
  Camera& cam = out.camera;
  cam.width = width;
  cam.height = height;
  // pbrt's fov spans the shorter image axis; montecl's fov_y the vertical one.
  const double fov = params.getFloat("fov", 90.0);
  if (!(fov > 0.0 && fov < 180.0)) pbrtFail(params.loc, "Camera: 'float fov' must be in (0, 180) degrees, got " + std::to_string(fov));
  double fovY = fov;
  if (width < height) fovY = glm::degrees(2.0 * std::atan(std::tan(glm::radians(fov) * 0.5) * double(height) / double(width)));
  cam.fovY = float(fovY);
  const double lens = params.getFloat("lensradius", 0.0);
  const double focal = params.getFloat("focaldistance", 1e6);
  if (!(lens >= 0.0)) pbrtFail(params.loc, "Camera: 'float lensradius' must be >= 0");
  if (!(focal > 0.0)) pbrtFail(params.loc, "Camera: 'float focaldistance' must be > 0");
  cam.position = glm::vec3(pos);
  cam.target = glm::vec3(pos + forward);
  cam.up = glm::vec3(up);
  if (lens > 0.0) {
    cam.apertureRadius = float(lens);
    cam.focusDistance = float(focal);
  }
  const CameraProblem problem = cameraBasisProblem(cam);
  if (!problem.empty()) pbrtFail(params.loc, "Camera: the camera transformation gives an unusable camera (" + problem.key + " " + problem.problem + ")");
  const glm::dvec3 monteclRight = glm::normalize(glm::cross(forward, up));
  if (glm::dot(monteclRight, right) < 0.0) {
    out.worldMirror = reflectionThroughPlane(monteclRight, pos);  // the plane of forward and up at pos
    out.mirrored = true;
  }
  return out;
}

}  // namespace montecl
