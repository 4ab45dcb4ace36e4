// test_scenes.h: the analytic scenes of host/scene/builtin_scenes.h, for the tests.
#pragma once
#include "scene/builtin_scenes.h"

namespace montecl_test {
using montecl::addFloor;
using montecl::addQuad;
using montecl::finishScene;
using montecl::floorScene;
using montecl::wallScene;
}  // namespace montecl_test
