// cmd_render.cpp: `montecl render SCENE`: load the scene, apply command-line overrides, build the
// BVH, render on the chosen OpenCL device and write the image atomically.
#include <signal.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <limits>
#include <optional>
#include <set>
#include <sstream>

#include "bvh/bvh.h"
#include "bvh/bvh_instances.h"
#include "cl/device_tuning.h"
#include "cl/devices.h"
#include "cli/commands.h"
#include "cli/render_args.h"
#include "cli/render_output.h"
#include "cli/dark_image.h"
#include "cli/load_steps.h"
#include "cli/render_signals.h"
#include "cli/render_views.h"
#include "cli/view_output.h"
#include "job/job.h"
#include "cli/validators.h"
#include "image/exr_layers.h"
#include "image/image_io.h"
#include "image/oidn_denoiser.h"
#include "render/emitters.h"
#include "render/integrators.h"
#include "image/provenance.h"
#include "render/progress.h"
#include "render/stage_program.h"
#include "render/wavefront.h"
#include "scene/camera_basis.h"
#include "scene/environment_key.h"
#include "scene/load_util.h"
#include "scene/scene.h"
#include "texture/scene_textures.h"
#include "texture/texture_identity.h"
#include "scene/scene_digest.h"
#include "util/atomic_file.h"
#include "util/errors.h"
#include "util/heap_trim.h"

namespace montecl {
namespace {

// What `montecl merge` checks before combining this render with others (image/provenance.h).
Provenance provenanceOf(const RenderArgs& a, const Scene& scene, const std::string& identityExtra) {
  Provenance p;
  p.version = MONTECL_VERSION;
  p.scene = sceneDigest(scene);
  p.settings = integratorSettings(scene.render) + (identityExtra.empty() ? "" : " " + identityExtra);
  const bool adaptive = a.targetError > 0.0 || scene.render.adaptive;
  if (a.targetError > 0.0) {
    std::ostringstream s;
    s << "target_error=" << a.targetError << " min_spp=" << a.minSpp << " max_spp=" << a.maxSpp;
    p.adaptive = s.str();
  } else if (scene.render.adaptive) {  // a pixel's samples are a prefix of [first, first + max_spp)
    std::ostringstream s;
    s << "budget spp=" << scene.render.spp << " min_spp=" << a.minSpp << " max_spp=" << a.maxSpp;
    p.adaptive = s.str();
  } else {
    p.adaptive = "off";
  }
  const std::uint64_t count = adaptive ? std::uint64_t(a.maxSpp) : std::uint64_t(scene.render.spp);
  p.samples = {{scene.render.seed, a.firstSample, std::uint64_t(a.firstSample) + count}};
  return p;
}

int runRender(const RenderArgs& a) {
  // Option rules first, before any file is read or kernel built.
  if (a.targetError > 0.0 && a.minSpp > a.maxSpp)
    throwInputError("--min-spp", "", "must not exceed --max-spp (" + std::to_string(a.maxSpp) + ")");
  // The budget in bytes must fit 64 bits (2^44 MiB and more would wrap to 0: every texture 1x1).
  if (a.textureBudgetMiB && !(*a.textureBudgetMiB * double(1 << 20) < 18446744073709551616.0))
    throwInputError("--texture-budget", "", "too large: at most 2^44 MiB (a 64-bit byte count)");
  checkOutputPattern(a.output, a.cameras);
  if (a.cameras.batch()) {  // several views: options that name one image or one camera position
    if (!a.job.checkpoint.empty() || !a.job.resume.empty())
      throwInputError(a.job.checkpoint.empty() ? "--resume" : "--checkpoint", "",
                      "a checkpoint holds one view: render the cameras one at a time (--camera N) to checkpoint them");
    if (!a.lookFrom.empty() || !a.lookAt.empty())
      throwInputError(a.lookFrom.empty() ? "--look-at" : "--look-from", "",
                      "would move every camera of --camera " + std::string(a.cameras.all ? "all" : "N,M,...") +
                          " to one place: give one camera (--camera N)");
  }
  std::vector<std::string> warnings;
  // --missing-textures decides while the loaders run (the other settings apply after loading).
  std::optional<MissingTextures> missing;
  if (const auto it = a.settings.find("missing_textures"); it != a.settings.end()) {
    RenderSettings chosen;
    for (const RenderSetting& s : renderSettings())
      if (s.key == "missing_textures") setFromText(s, it->second, chosen);
    missing = chosen.missingTextures;
  }
  // From here a signal ends the load at once (cli/render_signals.h); slow steps say so on stderr.
  InterruptGuard guard;
  LoadSteps steps(!a.quiet);
  listEveryWarning(a.verbose);  // -v: every warning of a kind, not the first and a count
  steps.begin("reading " + a.scene);
  Scene scene = loadScene(a.scene, warnings, missing, a.gltfScene);
  steps.finish();
  for (const std::string& w : warnings) std::cerr << "montecl: warning: " << w << "\n";
  applyOverrides(a, scene);
  // A budget (--adaptive) and a target error are two rules for the same samples.
  if (scene.render.adaptive && a.targetError > 0.0)
    throwInputError("--adaptive", "", "not with --target-error: --adaptive shares out a budget (--spp, --time), "
                                      "--target-error samples each pixel to an error; pick one");
  // --adaptive --time T without --spp: the time is the budget (rounds go on until it is up, or
  // until every pixel has --max-spp), not the scene file's spp.
  if (scene.render.adaptive && a.timeLimit > 0.0 && !a.settings.count("spp")) scene.render.spp = a.maxSpp;
  if (scene.render.adaptive && a.maxSpp < scene.render.spp)
    throwInputError("--max-spp", "", std::to_string(a.maxSpp) + " is below the --adaptive budget of " +
                                         std::to_string(scene.render.spp) + " spp: raise --max-spp (the most one pixel gets)");
  if (filterHasNegativeLobes(scene.render.filter))
    std::cerr << "montecl: warning: filter " << filterText(scene.render.filter)
              << ": its negative lobes are clamped to 0 (importance sampling draws offsets from max(0, filter))\n";
  const std::vector<unsigned> fileCameras = resolveCameras(a.cameras, scene.fileCameras.size(), scene.path);
  // The views: one per camera asked for (else the scene's camera), each with its own image; every
  // name is checked before any work.
  std::vector<RenderView> views;
  const std::size_t viewCount = fileCameras.empty() ? 1 : fileCameras.size();
  for (std::size_t v = 0; v < viewCount; ++v) {
    RenderView view;
    const std::optional<unsigned> cam = fileCameras.empty() ? std::nullopt : std::optional<unsigned>(fileCameras[v]);
    view.camera = viewCamera(a, scene, cam);
    view.fileCamera = cam ? int(*cam) : -1;
    if (!a.output.empty())
      view.output = cam ? expandOutputPattern(a.output, *cam) : a.output;
    else  // <scene name>.png, or <scene name>_<camera>.png for each of several
      view.output = defaultOutput(a.scene, a.overwrite, view.outputNote,
                                  a.cameras.batch() ? "_" + std::to_string(*cam) : std::string());
    checkOutputPath(view.output);
    if (!a.aovs.empty() && !isExr(view.output))
      throwInputError(view.output, "--aov", "AOVs need an .exr output");
    checkOutputIsNoInput(view.output, scene);
    checkWritableTarget(view.output);
    checkJobFiles(a.job.checkpoint, a.job.resume, view.output, scene);
    views.push_back(std::move(view));
  }
  scene.camera = views[0].camera;
  if (scene.fileCameras.size() > 1 && !a.cameras.given && a.view.empty())
    std::cerr << "montecl: warning: " << scene.path << ": " << scene.fileCameras.size()
              << " cameras; camera 0 is used (--camera N picks camera N, from 0; --camera all renders each)\n";
  // The denoiser is loaded and its device committed now, so a missing or broken library is one line
  // before any work, not after it.
  if (scene.render.denoise)
    if (const std::string problem = oidnProblem(); !problem.empty()) throw InputError(problem);
  // Sample indices are 32-bit: a range past 2^32 would wrap to sample 0 while the provenance says otherwise.
  const bool perPixelCounts = a.targetError > 0.0 || scene.render.adaptive;
  const std::uint64_t sampleCount = perPixelCounts ? std::uint64_t(a.maxSpp) : std::uint64_t(scene.render.spp);
  if (std::uint64_t(a.firstSample) + sampleCount > (std::uint64_t(1) << 32))
    throwInputError("--first-sample", "", std::to_string(a.firstSample) + " + " + std::to_string(sampleCount) +
                                              (perPixelCounts ? " (--max-spp)" : " (spp)") +
                                              " samples run past sample index 4294967295");
  DeviceInfo device = selectDevice(jobs::deviceSpec(a.device));
  guard.reinstall();
  // Instances render through the two-level BVH, which only the wide layout traverses.
  const BvhLayout askedLayout = parseBvhLayout(a.bvhLayout);
  const bool instanced = !scene.instances.empty();
  if (instanced && askedLayout == BvhLayout::Binary)
    throwInputError(scene.path, "--bvh-layout", "binary cannot render the scene's instances (no two-level form); use wide or auto");
  BvhLayout layout = instanced ? BvhLayout::Wide : resolveStageLayout(askedLayout, device);

  // Textures: every file once, under the budget (automatic: 1 GiB, at most the device's largest
  // allocation); a bad file is an input error before anything renders.
  const std::uint64_t textureBudget =
      a.textureBudgetMiB ? std::uint64_t(*a.textureBudgetMiB * double(1 << 20))
                         : defaultTextureBudget(device);
  std::vector<std::string> textureWarnings;
  const auto textureStart = std::chrono::steady_clock::now();
  // The film accumulates every AOV when it has any (a checkpoint keeps them all): the albedo AOV
  // reads the reflectance textures, the normal AOV the normal maps, so a film with AOVs
  // reads both; the denoiser's albedo and normal guides are these AOVs.
  const bool filmAovs = !a.aovs.empty() || scene.render.denoise;
  steps.begin("loading textures");
  const SceneTextures textures = loadSceneTextures(
      scene, textureBudget, textureWarnings, textureUsesOf(integratorDesc(scene.render.integrator), filmAovs));
  const double textureMs =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - textureStart).count();
  for (const std::string& w : textureWarnings) std::cerr << "montecl: warning: " << scene.path << ": " << w << "\n";
  BvhBuildOptions buildOptions;
  buildOptions.splitBudget = a.splitBudget;
  steps.begin("building the BVH");
  Bvh bvh = buildSceneBvh(scene, buildOptions);
  steps.finish();
  const bool lit = integratorDesc(scene.render.integrator).lit &&
                   !scene.environment.enabled && scene.lights.empty();  // these light the scene by themselves
  const bool saidBlack = lit && !hasEmitter(scene);  // the dark-image warning would repeat this one
  if (saidBlack)
    std::cerr << "montecl: warning: " << scene.path << ": integrator " << choiceName(scene.render.integrator)
              << " but nothing emits (no Ke, no mesh "
              << "\"emission\"): the image is black\n";
  else if (lit && !emittersFaceAnything(scene))
    std::cerr << "montecl: warning: " << scene.path << ": no emitter's front face faces any surface (emitters "
              << "light from the side of cross(v1 - v0, v2 - v0)): only the emitters will show; flip their "
              << "winding or set \"two_sided_emission\": true on the mesh\n";
  if (a.verbose) {
    std::cerr << "montecl: " << scene.triangles.size() << " triangles (" << scene.degenerateDropped
              << " degenerate dropped), " << scene.materials.size() << " materials"
              << (instanced ? ", " + std::to_string(scene.instances.size()) + " instances of " +
                                  std::to_string(scene.meshRanges.size()) + " meshes (two-level BVH)"
                            : std::string())
              << "\n"
              << "montecl: BVH built in " << bvh.buildMs << " ms: " << bvh.nodes.size() << " nodes, depth "
              << bvh.depth << ", SAH cost " << bvh.sahCost << ", " << bvh.triangles.size()
              << " triangle references\n"
              << "montecl: device " << device.platformIndex << ":" << device.deviceIndex << " " << device.name
              << ", " << bvhLayoutName(layout) << " BVH layout, " << resolveLanes(a.lanes, device)
              << " lanes\n";
    for (const RenderView& view : views) std::cerr << "montecl: " << cameraJson(view.camera) << "\n";
    if (!scene.defaultsNote.empty() && a.env.empty()) std::cerr << "montecl: environment: " << scene.defaultsNote << "\n";
    if (!textures.textures.empty())
      std::cerr << "montecl: " << textures.textures.size() << " textures, " << textures.levels.size()
                << " mip levels, " << (textures.bytes() >> 20) << " MiB of texels (budget " << (textureBudget >> 20)
                << " MiB), loaded in " << textureMs << " ms\n";
  }
  RenderOptions options;
  options.waveSize = a.waveSize;
  options.firstSample = a.firstSample;
  options.targetError = a.targetError;
  options.minSpp = a.minSpp;
  options.maxSpp = a.maxSpp;
  options.timeLimit = a.timeLimit;
  options.interrupt = renderInterruptFlag();
  options.wavesStart = [&steps] {  // loading is over: a signal now stops after a wave
    endLoading();
    steps.finish();
  };
  options.aovs = filmAovs;
  options.workGroupSize = a.workGroupSize;
  options.lanes = a.lanes;
  options.fuseWaves = !a.noFuse;
  options.bvhLayout = layout;
  options.verbose = a.verbose;
  options.profile = a.profile;
  options.identityExtra = textureBudgetIdentity(textures);
  // Everything that reads the scene's triangles runs now, for every view: the provenance digest,
  // the job's checkpoint key and the renderer's per-triangle table; then they are freed (only the
  // BVH's arrays and that table are uploaded), which lowers the peak by their size.
  std::vector<std::unique_ptr<jobs::Job>> jobsOfViews;
  for (RenderView& view : views) {
    scene.camera = view.camera;
    if (isExr(view.output)) view.provenance = provenanceOf(a, scene, options.identityExtra);
    jobsOfViews.push_back(std::make_unique<jobs::Job>(a.job, scene, options));
  }
  RenderPart part;
  part.textures = &textures;
  steps.begin("preparing the triangles");
  PreparedTriangles triangles = prepareTriangles(scene, bvh);
  part.triangles = &triangles;
  std::vector<SceneTriangle>().swap(scene.triangles);
  std::vector<glm::vec4>().swap(scene.vertexTangents);  // in the table too (prepareTriangles)
  trimHeap();
  steps.begin("building the kernels");
  WavefrontRenderer renderer(device, options);
  guard.reinstall();
  if (a.verbose)
    std::cerr << "montecl: kernels " << (renderer.programFromCache() ? "loaded from cache" : "compiled") << " in "
              << renderer.programBuildMs() << " ms\n";

  // Each view in turn through the one renderer (the scene, textures, BVH and kernels are shared);
  // a signal stops the view under way, which is written, and the rest are left out.
  for (std::size_t v = 0; v < views.size(); ++v) {
    if (v > 0 && *renderInterruptFlag()) {
      std::cout << "interrupted: " << views.size() - v << " of " << views.size() << " views not rendered\n";
      return *renderInterruptFlag() == SIGTERM ? kExitTerminated : kExitInterrupted;
    }
    scene.camera = views[v].camera;
    RenderStats stats;
    ProgressBar bar(!a.quiet);
    // The lights' and the device's tables are built inside the render, before its first wave.
    steps.begin("preparing lights and device tables");
    jobs::Job& job = *jobsOfViews[v];
    part.keepTriangles = v + 1 < views.size();  // the last view takes the tables, the others copy them
    Film film = job.render(renderer, scene, bvh, stats, [&](std::uint64_t done, std::uint64_t total, const RenderStats& s) {
      bar.update(done, total, s);
    }, part);
    endLoading();
    steps.finish();
    bar.finish();
    if (a.profile) std::cout << formatProfile(stats.profile, stats.seconds);
    if (stats.nanRays > 0)  // each rank of an MPI job warns about its own pixels
      std::cerr << "montecl: warning: " << stats.nanRays
                << " rays with NaN/inf origin or direction were treated as misses\n";
    if (!job.writesImage()) continue;
    const int status = writeView(a, scene, views[v], film, stats, saidBlack);
    if (status != kExitOk) {
      if (v + 1 < views.size())
        std::cout << "interrupted: " << views.size() - v - 1 << " of " << views.size() << " views not rendered\n";
      return status;
    }
  }
  return kExitOk;
}

}  // namespace

// `render --help` in groups, the options most renders set first: the common ones (output, size,
// device, integrator, samples, environment, view), then the integrators' settings, then adaptive
// sampling, time limits and split or resumable renders, then the knobs that change speed or memory.
const char* const kSettingsGroup = "Integrator and sampling settings (a scene file's render keys)";
const char* const kRunsGroup = "Adaptive sampling, time limits, split and resumable renders";
const char* const kTuning = "Tuning (speed and memory; the image is the same for any value unless noted)";
// The render settings listed with the common options.
const std::set<std::string> kCommonSettings = {"integrator", "spp", "seed", "denoise", "missing_textures"};

void addRenderCommand(CLI::App& app, int& exitCode) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* cmd = app.add_subcommand("render", "Render a scene file (.json) or a bare mesh (.obj, .ply, .gltf, .glb)");
  cmd->add_option("scene", args->scene, "Scene file (.json or pbrt-v4 .pbrt) or a bare mesh (.obj, .ply, .gltf, .glb)")->required();
  cmd->add_option("-o,--output", args->output,
                  "Output image: .png (8-bit sRGB), .pfm (linear float), .exr (linear float with channels R, G, B, "
                  "samples, var.R, var.G, var.B); default: <scene name>.png in the current folder (<folder "
                  "name>.png for a scene.json), never replacing a file: <name>-1.png, ... unless --overwrite");
  cmd->add_flag("--overwrite", args->overwrite, "Let the default output name replace an existing file");
  cmd->add_option("--width", args->width, "Image width in pixels (up to 16384)")->check(positiveInteger(kMaxImageSide));
  cmd->add_option("--height", args->height, "Image height in pixels (up to 16384)")->check(positiveInteger(kMaxImageSide));
  cmd->add_option("--device", args->device, "OpenCL device: P:D, part of the device or platform name, or host (CPU, no OpenCL); default: "
                  "the first GPU, else the first CPU device (`montecl devices` lists them)");
  // Every render setting with an option (scene/render_settings.h): the scene file's rule and help.
  for (const RenderSetting& setting : renderSettings()) {
    if (setting.option.empty()) continue;
    const std::string key = setting.key;
    cmd->option_defaults()->group(kCommonSettings.count(key) ? "Options" : kSettingsGroup);
    if (setting.rule.kind == SettingRule::Bool) {  // a flag: present means true
      cmd->add_flag_function(
          setting.option, [args, key](std::int64_t) { args->settings[key] = "true"; },
          setting.help + " (scene file: render." + key + ", default " + settingValueText(setting.get(RenderSettings{})) + ")");
      continue;
    }
    // A bare model is path traced (applyBareModelDefaults): the help says so beside the table's default.
    const std::string bare = key == "integrator" ? "; path for a bare model" : "";
    cmd->add_option_function<std::string>(
           setting.option, [args, key](const std::string& v) { args->settings[key] = v; },
           setting.help + " (scene file: render." + key + ", default " + settingValueText(setting.get(RenderSettings{})) +
               bare + ")")
        ->check(CLI::Validator([&setting](std::string& text) { return settingTextProblem(setting, text); },
                               setting.rule.text))
        ->type_name(setting.rule.kind == SettingRule::Choice   ? "NAME"
                    : setting.rule.kind == SettingRule::Filter ? "FILTER"
                    : setting.rule.kind == SettingRule::Integer ? "INT" : "FLOAT");
  }
  cmd->option_defaults()->group("Options");
  cmd->add_option("--aov", args->aovs,
                  "Extra EXR channels, comma-separated: albedo (albedo.R/G/B), normal (N.X/Y/Z), depth (Z), "
                  "emission (emission.R/G/B: emitted radiance seen directly), or all; averaged over each "
                  "pixel's samples")
      ->delimiter(',')
      ->check(CLI::IsMember({"albedo", "normal", "depth", "emission", "all"}));
  cmd->add_option("--env", args->env,
                  "Environment light replacing the scene's: R,G,B (constant radiance), a latitude-longitude "
                  "map file (.exr, .hdr, ...), or none (a bare model gets a white sky: radiance 1, or 0.25 when "
                  "it brings its own lights)");
  cmd->add_option("--env-scale", args->envScale, "Multiplies --env's radiance (default 1)");
  cmd->add_option("--env-rotate", args->envRotate, "Rotates --env's map about +y, degrees (default 0)");
  cmd->add_option("--view", args->view,
                  "Frame the whole model from a side, replacing the scene's camera: front (+z, a bare mesh's "
                  "default) | back | left | right | top | bottom | iso");
  cmd->add_option_function<std::string>(
         "--camera", [args](const std::string& v) { args->cameras = parseCameraRequest(v); },
         "Render through the model file's camera N (a glTF file's perspective cameras, from 0, in the order its "
         "nodes meet them; default: the first, else the automatic framing); N,M,... or all: one image per camera, "
         "-o naming them by a pattern with {camera} (out_{camera}.png), loading the scene and kernels once")
      ->check(CLI::Validator([](std::string& text) { return cameraRequestProblem(text); }, "N|N,M,...|all"))
      ->type_name("N|all")
      ->excludes("--view");
  cmd->add_option("--scene", args->gltfScene,
                  "Load the glTF model's scene N (its scenes[], from 0; default: the file's \"scene\", else 0)");
  cmd->add_option("--look-from", args->lookFrom, "Camera position X,Y,Z, replacing the chosen camera's (scene units)");
  cmd->add_option("--look-at", args->lookAt, "Point the camera looks at, X,Y,Z, replacing the chosen camera's");
  cmd->add_option("--fov", args->fov, "Vertical field of view in degrees, replacing the camera's (up to 179.9)")
      ->check(positiveNumber(179.9));
  cmd->add_flag("-q,--quiet", args->quiet, "No progress bar");
  cmd->add_flag("-v,--verbose", args->verbose, "Scene, BVH, device and wave details on stderr");
  cmd->option_defaults()->group(kRunsGroup);
  cmd->add_option("--target-error", args->targetError,
                  "Adaptive sampling: sample until each pixel's relative standard error (stderr / max(mean "
                  "luminance, 0.01)) is at most this, between --min-spp and --max-spp; ignores --spp")
      ->check(positiveNumber());
  cmd->add_option("--min-spp", args->minSpp,
                  "Adaptive sampling: samples every pixel gets first (default 16; with --adaptive at most --spp)")
      ->check(integerIn(2, 1 << 24, "an integer from 2 to 16777216"));
  cmd->add_option("--max-spp", args->maxSpp,
                  "Adaptive sampling: most samples a pixel gets (default 1024; with --adaptive at least --spp)")
      ->check(integerIn(2, 1 << 24, "an integer from 2 to 16777216"));
  cmd->add_option("--time", args->timeLimit,
                  "Stop after the wave that crosses this many seconds and write the image so far")
      ->check(positiveNumber());
  cmd->add_option("--first-sample", args->firstSample,
                  "Render sample indices K .. K+spp-1 of the deterministic sequence (split renders, then merge)");
  jobs::addJobOptions(cmd, args->job);
  cmd->option_defaults()->group(kTuning);
  cmd->add_option("--wave-size", args->waveSize, "Pixel samples per wave (default: sized from the measured rate, at most 8192 per CPU compute unit, 2^20 on GPUs)")
      ->check(integerIn(1, std::numeric_limits<long long>::max(), "a positive integer"))
      ->group(kTuning);
  cmd->add_option("--texture-budget", args->textureBudgetMiB,
                  "Device memory for textures in MiB (default: 1024, at most the device's largest allocation); "
                  "over it, the finest mip levels are dropped with a warning")
      ->check(positiveNumber())
      ->group(kTuning);
  cmd->add_option("--work-group-size", args->workGroupSize, "Work-group size (default: min(64, kernel max))")
      ->check(positiveInteger())
      ->group(kTuning);
  cmd->add_option("--lanes", args->lanes,
                  "Items per work item of the packet stages, in vector lanes: 1 | 4 | 8 | 16 (default: the "
                  "device's, `montecl devices`; the host backend runs 1); images are the same for every value")
      ->check(CLI::IsMember({1u, 4u, 8u, 16u}))
      ->group(kTuning);
  cmd->add_flag("--no-fuse", args->noFuse,
                "Launch every stage of a wave as its own kernel (default: AO and direct waves run as one fused "
                "kernel on devices with packet stages); images are the same either way")
      ->group(kTuning);
  cmd->add_option("--split-budget", args->splitBudget,
                  "BVH spatial splits: at most this many extra triangle references per triangle (0: none)")
      ->check(finiteIn(0.0, 4.0))
      ->group(kTuning);
  cmd->add_option("--bvh-layout", args->bvhLayout,
                  "BVH the kernels traverse: auto (binary on GPUs, wide otherwise) | wide | binary")
      ->check(CLI::IsMember({"auto", "wide", "binary"}))
      ->group(kTuning);
  cmd->add_flag("--profile", args->profile,
                "Print each stage's share of the render time (OpenCL profiling events; host timers on --device host)")
      ->group(kTuning);
  cmd->callback([args, &exitCode]() { exitCode = runRender(*args); });
}

}  // namespace montecl
