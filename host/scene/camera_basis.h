// camera_basis.h: the camera's basis (the pinhole, and the thin lens's centre) in the precision
// the renderer uses (float), and the check that it is usable. The kernels get exactly this basis
// (render/frame_params.cpp), so a camera that passes here yields finite camera rays; one that
// does not is bad input, caught at scene load with the key to fix, not a NaN image or a crash
// later.
#pragma once
#include <string>

#include "scene/scene.h"

namespace montecl {

struct CameraBasis {
  glm::vec3 forward, right, up;  // orthonormal (for a valid camera)
  glm::vec3 topLeft;             // direction through the top-left corner of pixel (0, 0)
  glm::vec3 dx, dy;              // steps of one pixel right and down
};

// The float basis of camera (the same operations, in the same order, as the kernels have always
// been given).
CameraBasis cameraBasis(const Camera& camera);

// Why a camera is unusable, or empty when it is fine: the one camera rule, for scene files, glTF
// cameras, automatic framing and cameras set in code (a field of view in (0, 180), a view
// direction, an up not along it, and a float basis the renderer can build). `key` is the camera
// key to change (camera.position, camera.target, camera.up or camera.fov_y), `problem` one line.
struct CameraProblem {
  std::string key, problem;
  bool empty() const { return key.empty(); }
};
CameraProblem cameraBasisProblem(const Camera& camera);

// The reflection through the plane of unit normal n through point p: x -> x - 2 n (n . (x - p)).
// The scene readers reflect the world with it where a file's camera mirrors montecl's.
glm::dmat4 reflectionThroughPlane(const glm::dvec3& n, const glm::dvec3& p);

}  // namespace montecl
