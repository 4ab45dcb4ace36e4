// view_output.cpp: writeView (view_output.h): one view's film to its image file and summary line.
#include "cli/view_output.h"

#include <signal.h>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <vector>

#include "cli/dark_image.h"
#include "cli/render_output.h"
#include "cli/render_signals.h"
#include "image/exr_layers.h"
#include "image/image_io.h"
#include "render/progress.h"
#include "util/errors.h"

namespace montecl {

int writeView(const RenderArgs& a, const Scene& scene, const RenderView& view, Film& film, const RenderStats& stats,
              bool saidBlack) {
  const std::string& output = view.output;
  const int signalled = *renderInterruptFlag();
  const bool interrupted = signalled && stats.stoppedEarly;  // a signal after the last wave changes nothing
  // Only the final image is denoised (an MPI job's rank 0, after the merge of the ranks' films).
  double denoiseSeconds = 0.0;
  std::vector<float> denoised;
  // The render is done: a denoiser that fails now (memory, a device lost) costs the denoised planes,
  // not the image.
  if (scene.render.denoise) try {
      denoised = denoiseFilm(film, scene.render.denoiseQuality, a.quiet, denoiseSeconds);
    } catch (const RuntimeError& e) {
      std::cerr << "montecl: warning: " << e.what() << "; " << output << " holds the image without denoising\n";
    }
  // The image as written: every EXR plane (the noisy estimate exactly, plus denoised.R/G/B), or the
  // mean (denoised with --denoise) for PNG/PFM; refused if a value overflowed.
  LayeredImage img;
  if (isExr(output)) {
    img = renderLayers(film, a.aovs);
    if (!denoised.empty()) addRgbPlanes(img, "denoised.", denoised);
    setProvenance(img, view.provenance);
  } else {
    img.width = film.width;
    img.height = film.height;
    addRgbPlanes(img, "", denoised.empty() ? film.meanRgb() : denoised);
  }
  if (std::size_t bad = nonFinitePixels(img))
    throw RuntimeError(std::to_string(bad) + " of " + std::to_string(img.pixelCount()) +
                       " pixels hold NaN or infinite values (radiance overflows a float: check emission and camera); " +
                       output + " was not written");
  if (!interrupted && !saidBlack)
    if (const std::string dark = darkImageWarning(denoised.empty() ? film.meanRgb() : denoised, scene); !dark.empty())
      std::cerr << "montecl: warning: " << (view.fileCamera >= 0 ? output + ": " : std::string()) << dark << "\n";
  if (isExr(output))
    writeLayeredExr(output, img);
  else
    writeRgbImage(output, film.width, film.height, denoised.empty() ? film.meanRgb() : denoised);
  std::cout << "wrote " << output << ": " << summaryLine(film.width, film.height, scene.render.spp, stats)
            << (a.job.resume.empty() ? "" : imageSamplesNote(film.count));
  if (!denoised.empty()) {
    char took[64];
    std::snprintf(took, sizeof took, ", denoised in %.3f s", denoiseSeconds);
    std::cout << took;
  }
  std::cout << view.outputNote << "\n";
  const std::uint64_t pixels = std::uint64_t(film.width) * film.height;
  if (a.targetError > 0.0)
    std::cout << "adaptive: " << stats.converged << " of " << pixels << " pixels within relative error "
              << a.targetError << ", " << stats.samples << " samples (" << double(stats.samples) / pixels
              << " per pixel) in " << stats.rounds << " rounds\n";
  if (scene.render.adaptive && !film.count.empty()) {
    const auto [fewest, most] = std::minmax_element(film.count.begin(), film.count.end());
    std::cout << "adaptive: " << stats.samples << " samples (" << double(stats.samples) / pixels
              << " per pixel, budget " << scene.render.spp << "), " << *fewest << " to " << *most
              << " per pixel, in " << stats.rounds << " groups\n";
  }
  if (stats.stoppedEarly)
    std::cout << (interrupted ? "interrupted" : "time limit reached") << ": " << stats.samples
              << " pixel samples done; the image holds each pixel's own sample count\n";
  if (!interrupted) return kExitOk;
  return signalled == SIGTERM ? kExitTerminated : kExitInterrupted;
}

}  // namespace montecl
