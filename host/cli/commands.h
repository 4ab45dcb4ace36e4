// commands.h: each montecl subcommand registers itself on the CLI11 app. Its callback runs the
// command and stores the exit code; errors are thrown (InputError -> 2, others -> 1) to main().
#pragma once
#include <CLI/CLI.hpp>

namespace montecl {

void addDevicesCommand(CLI::App& app, int& exitCode);
void addRenderCommand(CLI::App& app, int& exitCode);
void addIntegrateCommand(CLI::App& app, int& exitCode);
void addMergeCommand(CLI::App& app, int& exitCode);
void addBenchCommand(CLI::App& app, int& exitCode);     // cmd_bench.cpp
void addGenerateCommand(CLI::App& app, int& exitCode);  // cmd_generate.cpp
void addConformanceCommand(CLI::App& app, int& exitCode);  // cmd_conformance.cpp
void addSettingsCommand(CLI::App& app, int& exitCode);     // cmd_settings.cpp
void addKindsCommand(CLI::App& app, int& exitCode);        // cmd_kinds.cpp

}  // namespace montecl
