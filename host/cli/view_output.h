// view_output.h: what `montecl render` does with one view's film: denoise it when asked, make the
// image (EXR planes with provenance, or the mean), refuse it when a value overflowed, warn when it
// is nearly black, write it atomically and print its summary line. Writes the one output file.
#pragma once
#include <string>

#include "cli/render_args.h"
#include "image/film.h"
#include "image/provenance.h"
#include "render/wavefront.h"
#include "scene/scene.h"

namespace montecl {

// One image of a render: the camera it is seen through, where it is written (outputNote: what the
// summary adds about the name, e.g. that an existing file was kept), its provenance (EXR), and the
// file camera it came from (-1: the scene's camera).
struct RenderView {
  Camera camera;
  std::string output, outputNote;
  Provenance provenance;
  int fileCamera = -1;
};

// Writes view's image of film (the render of scene through view.camera, as stats says) and prints
// "wrote <output>: ..." (plus the adaptive and early-stop lines). saidBlack: the "nothing emits"
// warning was printed already (no dark-image warning on top of it). Returns the exit status: 0, or
// 130 / 143 when a signal stopped the render early. Throws RuntimeError (nothing written) when a
// pixel is not finite.
int writeView(const RenderArgs& a, const Scene& scene, const RenderView& view, Film& film, const RenderStats& stats,
              bool saidBlack);

}  // namespace montecl
