// suggest.cpp: nearestName and unknownNameHint (suggest.h): Levenshtein distance over the names
// CLI11 knows.
#include "cli/suggest.h"

#include <algorithm>
#include <cctype>

namespace montecl {
namespace {

std::size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

std::vector<std::string> optionNames(const CLI::App& cmd) {
  std::vector<std::string> names;
  for (const CLI::Option* o : cmd.get_options()) {
    for (const std::string& l : o->get_lnames()) names.push_back("--" + l);
    for (const std::string& s : o->get_snames()) names.push_back("-" + s);
  }
  return names;
}

}  // namespace

std::string nearestName(const std::string& word, const std::vector<std::string>& known) {
  const std::size_t limit = std::max<std::size_t>(2, word.size() / 3);
  std::string best;
  std::size_t bestDistance = limit + 1;
  for (const std::string& k : known) {
    const std::size_t d = editDistance(word, k);
    if (d < bestDistance) bestDistance = d, best = k;
  }
  return best;
}

std::string unknownNameHint(CLI::App& app, int argc, char** argv) {
  std::vector<std::string> commands;
  for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) commands.push_back(sub->get_name());
  // The subcommand: the first word that is not an option of montecl itself.
  int at = 1;
  while (at < argc && argv[at][0] == '-') ++at;
  if (at >= argc) return "";
  const std::string word = argv[at];
  if (std::find(commands.begin(), commands.end(), word) == commands.end()) {
    std::string list;
    for (const std::string& c : commands) list += (list.empty() ? "" : ", ") + c;
    const std::string near = nearestName(word, commands);
    return "unknown command '" + word + "'" + (near.empty() ? "" : "; did you mean '" + near + "'?") +
           " (commands: " + list + ")";
  }
  CLI::App* cmd = app.get_subcommand(word);
  const std::vector<std::string> options = optionNames(*cmd);
  for (int i = at + 1; i < argc; ++i) {
    std::string arg = argv[i];
    if (arg == "--") break;
    if (arg.size() < 2 || arg[0] != '-' || (arg[1] != '-' && arg.size() == 2 && std::isdigit(arg[1]))) continue;
    if (arg[1] != '-' && arg.size() > 2) continue;  // -5 or a short option with its value
    arg = arg.substr(0, arg.find('='));
    if (std::find(options.begin(), options.end(), arg) != options.end()) continue;
    const std::string near = nearestName(arg, options);
    if (near.empty()) return "";
    return "unknown option '" + arg + "' of " + word + "; did you mean '" + near + "'?";
  }
  return "";
}

}  // namespace montecl
