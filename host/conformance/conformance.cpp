// conformance.cpp: runs the conformance set on the host backend (the reference) and on each
// selected OpenCL device: builds every kernel program (montecl.cl and integrate.cl), renders each
// case with the same seed and compares the mean images pixel by pixel (see conformance.h for the
// tolerance). A device whose build fails is reported with its build log and fails; so does a
// render that throws.
#include "conformance/conformance.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <sstream>

#include "bvh/bvh.h"
#include "bvh/bvh_instances.h"
#include "cl/cl_errors.h"
#include "cl/cl_session.h"
#include "cl/devices.h"
#include "cl/kernel_source.h"
#include "cl/program_cache.h"
#include "render/stage_program.h"
#include "render/wavefront.h"

namespace montecl {
namespace {

struct Rendered {
  Film film;
  RenderStats stats;
};

void compare(const Film& ref, const Film& dev, ImageComparison& c) {
  const std::vector<float> a = ref.meanRgb(), b = dev.meanRgb();
  if (a.size() != b.size() || ref.width != dev.width || ref.height != dev.height) {
    c.error = "image size differs from the host's";
    c.pass = false;
    return;
  }
  double sumAbs = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double x = a[i], y = b[i];
    const double diff = std::fabs(x - y), scale = std::max(std::fabs(x), std::fabs(y));
    sumAbs += diff;
    c.maxAbsDiff = std::max(c.maxAbsDiff, diff);
    c.maxRelDiff = std::max(c.maxRelDiff, diff / std::max(scale, kAbsFloor));
    if (!(diff <= std::max(kRelTolerance * scale, kAbsFloor))) ++c.failingValues;  // NaN fails
  }
  for (std::size_t p = 0; p < ref.mean.size(); ++p)
    if (ref.count[p] != dev.count[p]) ++c.failingValues;  // sample counts must match exactly
  if (ref.aovSum.size() != dev.aovSum.size()) {
    c.error = "AOV planes differ from the host's";
    ++c.failingValues;
  }
  for (std::size_t i = 0; i < ref.aovSum.size() && i < dev.aovSum.size(); ++i)  // AOVs: the same rule
    for (int k = 0; k < 4; ++k) {
      const double x = ref.aovSum[i][k], y = dev.aovSum[i][k];
      const double diff = std::fabs(x - y), scale = std::max(std::fabs(x), std::fabs(y));
      c.maxAbsDiff = std::max(c.maxAbsDiff, diff);
      if (!(diff <= std::max(kRelTolerance * scale, kAbsFloor))) ++c.failingValues;
    }
  c.meanAbsDiff = a.empty() ? 0.0 : sumAbs / double(a.size());
  // Bit for bit: every channel of the film's float-float mean and M2 (the variance), not only
  // the image.
  const std::vector<glm::vec4>* refParts[] = {&ref.mean, &ref.meanLo, &ref.m2, &ref.m2Lo};
  const std::vector<glm::vec4>* devParts[] = {&dev.mean, &dev.meanLo, &dev.m2, &dev.m2Lo};
  for (int k = 0; k < 4; ++k)
    for (std::size_t p = 0; p < refParts[k]->size() && p < devParts[k]->size(); ++p)
      for (int ch = 0; ch < 3; ++ch)
        if (std::memcmp(&(*refParts[k])[p][ch], &(*devParts[k])[p][ch], sizeof(float)) != 0) ++c.differingBits;
  for (std::size_t i = 0; i < ref.aovSum.size() && i < dev.aovSum.size(); ++i)
    for (int ch = 0; ch < 4; ++ch)
      if (std::memcmp(&ref.aovSum[i][ch], &dev.aovSum[i][ch], sizeof(float)) != 0) ++c.differingBits;
  // The sobol sampler's sub-sequence means and counts (the error estimate) too.
  if (ref.split.size() != dev.split.size()) {
    c.error = "sub-sequence accumulators differ from the host's";
    ++c.failingValues;
  }
  for (std::size_t i = 0; i < ref.split.size() && i < dev.split.size(); ++i)
    if (std::memcmp(&ref.split[i], &dev.split[i], sizeof(glm::vec4)) != 0) ++c.differingBits;
  // One image everywhere: a device passes only with the host's bits (the tolerance above reports
  // how far a failing image is, and catches gross errors when bits differ).
  c.pass = c.failingValues == 0 && c.differingBits == 0;
}

double mrays(const RenderStats& s) { return s.seconds > 0.0 ? double(s.raysTraced()) / s.seconds / 1e6 : 0.0; }

// Builds the separate integrate.cl program (montecl.cl is built by the renderer).
void buildIntegrateProgram(const DeviceInfo& device, DeviceReport& r) {
  cl::Context context(device.device);
  ProgramBuild b = buildProgramCached(context, device, expandedKernelSource("integrate.cl"), kKernelBuildOptions);
  r.buildMs += b.buildMs;
  r.fromCache = r.fromCache && b.fromCache;
}

}  // namespace

ConformanceReport runConformance(const ConformanceOptions& options) {
  ConformanceReport report;
  const std::vector<ConformanceCase> cases = conformanceSet(options.set, report.skipped);
  std::vector<Bvh> bvhs;
  for (const ConformanceCase& c : cases) bvhs.push_back(buildSceneBvh(c.scene));

  // Reference images from the host backend.
  std::vector<Rendered> reference(cases.size());
  {
    RenderOptions withAovs;
    withAovs.aovs = true;
    WavefrontRenderer host(hostDeviceInfo(), {}), hostAovs(hostDeviceInfo(), withAovs);
    double rays = 0.0, seconds = 0.0;
    for (std::size_t i = 0; i < cases.size(); ++i) {
      RenderPart part;
      part.textures = cases[i].textures.get();
      reference[i].film = (cases[i].aovs ? hostAovs : host).render(cases[i].scene, bvhs[i], reference[i].stats, {}, part);
      rays += double(reference[i].stats.raysTraced());
      seconds += reference[i].stats.seconds;
    }
    report.hostMrays = seconds > 0.0 ? rays / seconds / 1e6 : 0.0;
  }

  std::vector<DeviceInfo> devices;
  if (options.deviceSpecs.empty()) {
    DeviceList list = listDevices();
    devices = list.devices;
    report.platformErrors = list.platformErrors;
  } else {
    for (const std::string& spec : options.deviceSpecs) devices.push_back(selectDevice(spec));
  }

  report.pass = !devices.empty();
  for (const DeviceInfo& device : devices) {
    DeviceReport r;
    r.index = deviceIndexString(device);
    r.name = device.name;
    r.platform = device.platformName;
    std::unique_ptr<WavefrontRenderer> renderer, aovRenderer;  // (the AOV cases' renderer records AOVs)
    // Instanced cases where the layout under test is binary: the wide layout, as `render` picks.
    std::unique_ptr<WavefrontRenderer> wideRenderer, wideAovRenderer;
    try {
      RenderOptions ro;
      // --bvh-layout is for the OpenCL devices under test; the host backend, the reference, runs
      // its own (default) layout.
      ro.bvhLayout = device.isHost ? BvhLayout::Auto : options.bvhLayout;
      ro.lanes = device.isHost ? 0 : options.lanes;
      renderer = std::make_unique<WavefrontRenderer>(device, ro);
      ro.aovs = true;
      aovRenderer = std::make_unique<WavefrontRenderer>(device, ro);
      const bool instanced = std::any_of(bvhs.begin(), bvhs.end(), [](const Bvh& b) { return !b.instances.empty(); });
      if (instanced && !device.isHost && resolveStageLayout(ro.bvhLayout, device) == BvhLayout::Binary) {
        ro.bvhLayout = BvhLayout::Wide;
        wideAovRenderer = std::make_unique<WavefrontRenderer>(device, ro);
        ro.aovs = false;
        wideRenderer = std::make_unique<WavefrontRenderer>(device, ro);
      }
      r.buildMs = renderer->programBuildMs();
      r.fromCache = renderer->programFromCache();
      if (!device.isHost) buildIntegrateProgram(device, r);
      r.buildOk = true;
    } catch (const cl::Error& e) {
      r.buildError = describeClError(e);
    } catch (const std::exception& e) {
      r.buildError = e.what();
    }
    r.pass = r.buildOk;
    if (renderer) {
      // Warm-up, untimed: PoCL specialises each kernel on its first launch.
      for (Integrator integrator : {Integrator::Ao, Integrator::Direct}) {
        Scene tiny = cases.front().scene;
        tiny.camera.width = tiny.camera.height = 2;
        tiny.render.spp = 1;
        tiny.render.integrator = integrator;
        RenderStats ignored;
        try {
          renderer->render(tiny, bvhs.front(), ignored);
        } catch (const std::exception&) {
          // reported by the real renders below
        }
      }
    }
    for (std::size_t i = 0; i < cases.size(); ++i) {
      ImageComparison c;
      c.name = cases[i].name;
      c.width = cases[i].scene.camera.width;
      c.height = cases[i].scene.camera.height;
      c.spp = cases[i].scene.render.spp;
      if (renderer) {
        try {
          Rendered out;
          RenderPart part;
          part.textures = cases[i].textures.get();
          const bool wide = wideRenderer && !bvhs[i].instances.empty();
          WavefrontRenderer& run = *(cases[i].aovs ? (wide ? wideAovRenderer : aovRenderer) : (wide ? wideRenderer : renderer));
          out.film = run.render(cases[i].scene, bvhs[i], out.stats, {}, part);
          c.rendered = true;
          c.seconds = out.stats.seconds;
          c.mrays = mrays(out.stats);
          compare(reference[i].film, out.film, c);
        } catch (const cl::Error& e) {
          c.error = describeClError(e);
        } catch (const std::exception& e) {
          c.error = e.what();
        }
      } else {
        c.error = "kernels did not build";
      }
      r.pass = r.pass && c.pass;
      r.images.push_back(c);
    }
    report.pass = report.pass && r.pass;
    report.devices.push_back(std::move(r));
  }
  return report;
}

nlohmann::json conformanceJson(const ConformanceReport& report) {
  nlohmann::json devices = nlohmann::json::array();
  for (const DeviceReport& d : report.devices) {
    nlohmann::json images = nlohmann::json::array();
    for (const ImageComparison& c : d.images)
      images.push_back({{"name", c.name},
                        {"width", c.width},
                        {"height", c.height},
                        {"spp", c.spp},
                        {"rendered", c.rendered},
                        {"maxAbsDiff", c.maxAbsDiff},
                        {"meanAbsDiff", c.meanAbsDiff},
                        {"maxRelDiff", c.maxRelDiff},
                        {"failingValues", c.failingValues},
                        {"differingBits", c.differingBits},
                        {"mrays", c.mrays},
                        {"seconds", c.seconds},
                        {"pass", c.pass},
                        {"error", c.error}});
    devices.push_back({{"index", d.index},
                       {"name", d.name},
                       {"platform", d.platform},
                       {"build", {{"ok", d.buildOk}, {"ms", d.buildMs}, {"fromCache", d.fromCache},
                                  {"error", d.buildError}}},
                       {"images", images},
                       {"pass", d.pass}});
  }
  return {{"reference", "host"},
          {"tolerance", {{"relative", kRelTolerance}, {"absoluteFloor", kAbsFloor}}},
          {"hostMrays", report.hostMrays},
          {"devices", devices},
          {"skipped", report.skipped},
          {"platformErrors", report.platformErrors},
          {"pass", report.pass}};
}

std::string conformanceTable(const ConformanceReport& report) {
  std::ostringstream out;
  char line[512];
  out << "reference: host backend (" << report.hostMrays << " Mrays/s); an image passes when every film value "
      << "has the host's bits (max abs/rel: how far it is; gross errors: beyond " << kRelTolerance
      << " relative, absolute floor " << kAbsFloor << ")\n";
  for (const DeviceReport& d : report.devices) {
    out << "\n" << d.index << "  " << d.name << " (" << d.platform << "): build "
        << (d.buildOk ? "ok" : "FAILED") << " (" << d.buildMs << " ms" << (d.fromCache ? ", cached" : "") << ")\n";
    if (!d.buildOk) out << "  " << d.buildError << "\n";
    std::snprintf(line, sizeof line, "  %-32s %9s %11s %11s %11s %9s  %s\n", "image", "size", "max abs", "mean abs",
                  "max rel", "Mrays/s", "result");
    out << line;
    for (const ImageComparison& c : d.images) {
      std::string size = std::to_string(c.width) + "x" + std::to_string(c.height) + "x" + std::to_string(c.spp);
      std::string result = c.pass ? "pass (bit-identical)"
                           : !c.error.empty()     ? "FAIL: " + c.error
                           : c.failingValues == 0 ? "FAIL (" + std::to_string(c.differingBits) + " values differ in their bits)"
                                                  : "FAIL (" + std::to_string(c.failingValues) + " values)";
      std::snprintf(line, sizeof line, "  %-32s %9s %11.3g %11.3g %11.3g %9.2f  %s\n", c.name.c_str(), size.c_str(),
                    c.maxAbsDiff, c.meanAbsDiff, c.maxRelDiff, c.mrays, result.c_str());
      out << line;
    }
  }
  for (const std::string& s : report.skipped) out << "skipped " << s << "\n";
  for (const std::string& e : report.platformErrors) out << "platform error: " << e << "\n";
  if (report.devices.empty()) out << "no OpenCL device found\n";
  out << (report.pass ? "conformance: all devices pass\n" : "conformance: FAILED\n");
  return out.str();
}

}  // namespace montecl
