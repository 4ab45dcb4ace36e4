// render_output.h: what `montecl render` does around its output image: the default name, the
// checks before rendering (the output is not an input), the EXR layers of a film, the count of
// non-finite pixels that refuses a write, the denoised image (Open Image Denoise, dlopened), and
// the camera as scene JSON for -v. Reads and writes no file except what defaultOutput looks at
// (whether names exist) and checkJobFiles (an existing checkpoint's magic, a probe file created
// and removed beside the checkpoint).
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "image/exr_layers.h"
#include "image/film.h"
#include "scene/scene.h"

namespace montecl {

// Whether a and b name one file: the same file when both exist (hard links too), else the same
// path once made absolute and normal (a file not yet written).
bool sameFile(const std::string& a, const std::string& b);
// Refuses (InputError) an output that is one of the files the render reads (scene, OBJ, MTL,
// textures), in any case of its letters (the loaders open a name in another case).
void checkOutputIsNoInput(const std::string& output, const Scene& scene);
// The files of --checkpoint and --resume, checked before any work: the output is not the resume
// checkpoint; the checkpoint is neither the output nor an input, is a montecl checkpoint when it
// exists already, and can be created (util/atomic_file.h checkWritableTarget). The checkpoint may be
// the resume file (a resumed render keeps saving to it). InputError (exit 2) otherwise.
void checkJobFiles(const std::string& checkpoint, const std::string& resume, const std::string& output,
                   const Scene& scene);
// Whether path ends in .exr (any case).
bool isExr(const std::string& path);
// The number of pixels with a NaN or infinite value in any plane (values that overflowed a float).
std::size_t nonFinitePixels(const LayeredImage& img);
// The EXR layers: R, G, B, samples, var.R/G/B, and the AOVs asked for, averaged over samples:
// albedo.R/G/B, N.X/Y/Z (facing geometric normal), Z (distance along the camera ray),
// emission.R/G/B (emission seen directly). The film's accumulators and AOV sums are freed as the
// planes are made (takeLayersFromFilm): afterwards it holds its size and sample counts only.
LayeredImage renderLayers(Film& film, const std::vector<std::string>& aovs);
// Open Image Denoise on the film's mean less its emission AOV (added back to the output), with its
// albedo and normal AOVs as guides (zero guides and nothing taken out when the film has none); a progress line on stderr unless quiet. Returns interleaved RGB and the filter's
// seconds. Throws RuntimeError if the library fails.
std::vector<float> denoiseFilm(const Film& film, DenoiseQuality quality, bool quiet, double& seconds);
// Adds planes <prefix>R, <prefix>G, <prefix>B from interleaved RGB ("" for the image itself).
void addRgbPlanes(LayeredImage& img, const std::string& prefix, const std::vector<float>& rgb);
// The camera as a scene-file "camera" entry, to copy into a scene file (-v).
std::string cameraJson(const Camera& c);
// The default output: <stem>.png in the current folder, named after the scene's folder when the
// file is scene.json (every shared scene is). An existing file is never replaced without
// --overwrite: the first free <name>-N.png is used instead, and `note` says so. suffix follows the
// name (one image of several views: "_2" for camera 2).
std::string defaultOutput(const std::string& scenePath, bool overwrite, std::string& note, const std::string& suffix = "");

}  // namespace montecl
