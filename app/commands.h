// The subcommands of `kdswap`; each file adds one to the CLI11 app.
#pragma once

#include <CLI/CLI.hpp>

namespace kdswap {

void addRenderCommand(CLI::App& app);
void addInfoCommand(CLI::App& app);
void addAnimateCommand(CLI::App& app);
void addBenchCommand(CLI::App& app);
void addExportCommand(CLI::App& app);

}  // namespace kdswap

namespace kdswap {

//! Thrown by a subcommand to end with a specific exit code after printing its own message.
struct CommandExit {
  int code;
};

}  // namespace kdswap
