// stage_profile.cpp: summing stage times by name and the `--profile` table (render/stage_profile.h).
#include "render/stage_profile.h"

#include <cstdio>

namespace montecl {

void StageProfile::add(const std::string& name, double ms) {
  for (StageTime& s : stages)
    if (s.name == name) {
      s.ms += ms;
      s.launches++;
      return;
    }
  stages.push_back(StageTime{name, ms, 1});
}

double StageProfile::stageMs() const {
  double sum = 0.0;
  for (const StageTime& s : stages) sum += s.ms;
  return sum;
}

std::string stageProfileName(Stage s, RayInput rays) {
  return std::string(stageName(s)) + (rays == RayInput::Bounce ? " (bounce rays)" : "");
}

std::string formatProfile(const StageProfile& profile, double wallSeconds) {
  const double wallMs = wallSeconds * 1e3;
  const auto share = [&](double ms) { return wallMs > 0.0 ? 100.0 * ms / wallMs : 0.0; };
  std::string out = "profile: share of the render's wall time (the wave loop)\n";
  char line[160];
  std::snprintf(line, sizeof line, "  %-28s %10s %7s %9s\n", "stage", "ms", "share", "launches");
  out += line;
  for (const StageTime& s : profile.stages) {
    std::snprintf(line, sizeof line, "  %-28s %10.3f %6.1f%% %9llu\n", s.name.c_str(), s.ms, share(s.ms),
                  static_cast<unsigned long long>(s.launches));
    out += line;
  }
  const double rest = wallMs - profile.stageMs();  // negative only if stage times were miscounted
  std::snprintf(line, sizeof line, "  %-28s %10.3f %6.1f%%\n", "host (device idle)", rest, share(rest));
  out += line;
  std::snprintf(line, sizeof line, "  %-28s %10.3f %6.1f%%\n", "total", wallMs, share(wallMs));
  out += line;
  out += "  host (device idle): host code, buffer transfers, waits and launch latency between stages\n";
  const std::uint64_t hits = profile.packedLanes + profile.aloneLanes;
  if (hits > 0) {
    std::snprintf(line, sizeof line, "shading: %.1f%% of %llu hits in lane types", 100.0 * double(profile.packedLanes) / double(hits),
                  static_cast<unsigned long long>(hits));
    out += line;
    out += " (the rest: material kinds without a lane form)\n";
  }
  return out;
}

}  // namespace montecl
