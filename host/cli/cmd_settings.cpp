// cmd_settings.cpp: `montecl settings [--markdown]`: the render settings table (scene/render_settings.h)
// as text, or as the markdown table docs/scene-format.md holds (a test keeps the two equal).
#include <iostream>

#include "cli/commands.h"
#include "scene/render_settings.h"
#include "util/errors.h"

namespace montecl {

void addSettingsCommand(CLI::App& app, int& exitCode) {
  CLI::App* cmd = app.add_subcommand("settings", "List the render settings: scene-file key, option, default, rule");
  auto markdown = std::make_shared<bool>(false);
  cmd->add_flag("--markdown", *markdown, "Print the table of docs/scene-format.md");
  cmd->callback([markdown, &exitCode]() {
    if (*markdown) {
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
