// cmd_settings.cpp: `montecl settings [--markdown | --json]`: the render settings table
// (scene/render_settings.h) as text, as the markdown table docs/scene-format.md holds (a test keeps
// the two equal), or as one JSON object of every key's default, for scripts (scripts/vs_mitsuba.py).
#include <iostream>
#include <nlohmann/json.hpp>
#include <variant>

#include "cli/commands.h"
#include "scene/render_settings.h"
#include "util/errors.h"

namespace montecl {
namespace {

// {"integrator": "ao", "spp": 64, ..., "background": [0, 0, 0]}: every setting's default, by key.
nlohmann::json settingDefaultsJson() {
  const RenderSettings defaults;
  nlohmann::json out = nlohmann::json::object();
  for (const RenderSetting& s : renderSettings()) {
    std::visit(
        [&](const auto& v) {
          using T = std::decay_t<decltype(v)>;
          if constexpr (std::is_same_v<T, glm::vec3>)
            out[s.key] = nlohmann::json::array({v.x, v.y, v.z});
          else
            out[s.key] = v;
        },
        s.get(defaults));
  }
  return out;
}

}  // namespace

void addSettingsCommand(CLI::App& app, int& exitCode) {
  CLI::App* cmd = app.add_subcommand("settings", "List the render settings: scene-file key, option, default, rule");
  auto markdown = std::make_shared<bool>(false);
  auto json = std::make_shared<bool>(false);
  CLI::Option* md = cmd->add_flag("--markdown", *markdown, "Print the table of docs/scene-format.md");
  cmd->add_flag("--json", *json, "Print every setting's default as one JSON object, by key")->excludes(md);
  cmd->callback([markdown, json, &exitCode]() {
    if (*json) {
      std::cout << settingDefaultsJson().dump() << "\n";
    } else if (*markdown) {
      std::cout << renderSettingsMarkdown();
    } else {
      const RenderSettings defaults;
      for (const RenderSetting& s : renderSettings())
        std::cout << "render." << s.key << (s.option.empty() ? "" : " (" + s.option + ")") << ": " << s.rule.text
                  << ", default " << settingValueText(s.get(defaults)) << "\n    " << s.help << "\n";
    }
    exitCode = kExitOk;
  });
}

}  // namespace montecl
