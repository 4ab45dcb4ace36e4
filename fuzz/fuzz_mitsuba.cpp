// fuzz_mitsuba.cpp: the Mitsuba XML fuzz entry (fuzz_entries.h): writes the bytes as fuzz.xml in
// the sandbox (beside tent.ply and part.xml, an included file) and loads them with loadScene();
// its seeds are small scenes through every tag family the reader knows. No sphere: each is 16k
// triangles, and mutants that repeat one hundreds of times only measure the tessellation.
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "fuzz_entries.h"
#include "scene/scene.h"
#include "util/errors.h"

namespace montecl_fuzz {
namespace {

namespace fs = std::filesystem;

void writeText(const fs::path& p, const std::string& s) {
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out << s;
  if (!out) throw std::runtime_error("fuzz: cannot write " + p.string());
}

// The files the seeds name, written beside fuzz.xml once (tent.ply is the sandbox's own).
void writeMitsubaFiles() {
  static const bool written = [] {
    writeText(fs::path(sandboxDir()) / "part.xml",
              "<scene version=\"3.0.0\"><shape type=\"disk\"><transform name=\"to_world\"><translate y=\"1\"/>"
              "</transform></shape></scene>\n");
    return true;
  }();
  (void)written;
}

const char* kHead =
    "<scene version=\"3.0.0\">\n<default name=\"spp\" value=\"4\"/>\n<default name=\"res\" value=\"8\"/>\n"
    "<integrator type=\"path\"><integer name=\"max_depth\" value=\"3\"/><integer name=\"rr_depth\" value=\"2\"/></integrator>\n"
    "<sensor type=\"perspective\"><float name=\"fov\" value=\"40\"/><string name=\"fov_axis\" value=\"y\"/>\n"
    "<transform name=\"to_world\"><lookat origin=\"0, 1, 5\" target=\"0, 1, 0\" up=\"0, 1, 0\"/></transform>\n"
    "<sampler type=\"independent\"><integer name=\"sample_count\" value=\"$spp\"/></sampler>\n"
    "<film type=\"hdrfilm\"><integer name=\"width\" value=\"$res\"/><integer name=\"height\" value=\"6\"/>"
    "<rfilter type=\"box\"/></film></sensor>\n";

}  // namespace

std::vector<std::string> mitsubaSeeds() {
  const std::string head = kHead;
  return {
      head + "<bsdf type=\"twosided\" id=\"white\"><bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"0.8\"/></bsdf></bsdf>\n"
             "<shape type=\"rectangle\"><ref id=\"white\"/><emitter type=\"area\"><rgb name=\"radiance\" value=\"4 4 4\"/></emitter>\n"
             "<transform name=\"to_world\"><scale value=\"0.5\"/><rotate x=\"1\" angle=\"90\"/><translate value=\"0 2 0\"/></transform></shape>\n"
             "<shape type=\"cube\"><bsdf type=\"conductor\"><string name=\"material\" value=\"Au\"/></bsdf>"
             "<transform name=\"to_world\"><matrix value=\"0.3 0 0 0  0 0.3 0 0.3  0 0 0.3 0  0 0 0 1\"/></transform></shape>\n"
             "<shape type=\"disk\"><point name=\"center\" x=\"1\" y=\"0.5\" z=\"0\"/><float name=\"radius\" value=\"0.3\"/>"
             "<bsdf type=\"dielectric\"><string name=\"int_ior\" value=\"bk7\"/></bsdf></shape>\n"
             "<shape type=\"disk\"><boolean name=\"flip_normals\" value=\"true\"/><bsdf type=\"thindielectric\"/></shape>\n"
             "</scene>\n",
      head + "<texture type=\"bitmap\" id=\"wood\"><string name=\"filename\" value=\"wood.png\"/>"
             "<string name=\"wrap_mode\" value=\"mirror\"/><transform name=\"to_uv\"><scale x=\"2\" y=\"3\"/></transform></texture>\n"
             "<shape type=\"ply\"><string name=\"filename\" value=\"tent.ply\"/><bsdf type=\"mask\">"
             "<texture name=\"opacity\" type=\"checkerboard\"/><bsdf type=\"roughplastic\"><ref name=\"diffuse_reflectance\" id=\"wood\"/>"
             "<float name=\"alpha\" value=\"0.2\"/></bsdf></bsdf></shape>\n"
             "<shape type=\"obj\"><string name=\"filename\" value=\"quad.obj\"/><bsdf type=\"bumpmap\">"
             "<texture type=\"bitmap\"><string name=\"filename\" value=\"wood.png\"/></texture>"
             "<bsdf type=\"roughconductor\"><string name=\"distribution\" value=\"ggx\"/><rgb name=\"eta\" value=\"0.2 0.9 1.1\"/>"
             "<rgb name=\"k\" value=\"3.9 2.4 2.1\"/></bsdf></bsdf></shape>\n"
             "<shape type=\"rectangle\"><bsdf type=\"roughdielectric\"><float name=\"int_ior\" value=\"1.33\"/>"
             "<float name=\"alpha_u\" value=\"0.1\"/><float name=\"alpha_v\" value=\"0.2\"/></bsdf><bsdf type=\"plastic\"/></shape>\n"
             "<emitter type=\"constant\"><spectrum name=\"radiance\" value=\"0.5\"/></emitter>\n"
             "</scene>\n",
      head + "<emitter type=\"point\"><point name=\"position\" value=\"0 3 0\"/><rgb name=\"intensity\" value=\"10\"/></emitter>\n"
             "<emitter type=\"spot\"><transform name=\"to_world\"><lookat origin=\"0 3 0\" target=\"0 0 0\" up=\"0 0 1\"/></transform>"
             "<float name=\"cutoff_angle\" value=\"30\"/><rgb name=\"intensity\" value=\"5\"/></emitter>\n"
             "<emitter type=\"directional\"><vector name=\"direction\" x=\"0\" y=\"-1\" z=\"0\"/><spectrum name=\"irradiance\" value=\"400:1, 700:2\"/></emitter>\n"
             "<emitter type=\"envmap\"><string name=\"filename\" value=\"wood.png\"/></emitter>\n"
             "<include filename=\"part.xml\"/>\n<medium type=\"homogeneous\"/>\n<shape type=\"cylinder\"/>\n"
             "<shape type=\"obj\"><string name=\"filename\" value=\"quad.obj\"/><bsdf type=\"principled\"/></shape>\n"
             "</scene>\n",
      "<scene version=\"0.6.0\"><integrator type=\"direct\"><integer name=\"emitterSamples\" value=\"2\"/></integrator>"
      "<sensor type=\"thinlens\"><float name=\"apertureRadius\" value=\"0.1\"/><float name=\"focusDistance\" value=\"4\"/>"
      "<transform name=\"toWorld\"><scale x=\"-1\"/><lookAt origin=\"0 1 5\" target=\"0 1 0\" up=\"0 1 0\"/></transform></sensor>"
      "<shape type=\"rectangle\"><bsdf type=\"diffuse\"><srgb name=\"reflectance\" value=\"0.5 0.2 0.1\"/></bsdf></shape></scene>\n",
  };
}

Outcome fuzzMitsuba(const std::uint8_t* data, std::size_t size) {
  writeMitsubaFiles();
  const fs::path p = fs::path(sandboxDir()) / "fuzz.xml";
  writeText(p, std::string(reinterpret_cast<const char*>(data), size));
  try {
    std::vector<std::string> warnings;
    montecl::loadScene(p.string(), warnings);
    return Outcome::Loaded;
  } catch (const montecl::InputError&) {
    return Outcome::Rejected;
  } catch (const montecl::RuntimeError&) {
    return Outcome::Rejected;
  }
}

}  // namespace montecl_fuzz
