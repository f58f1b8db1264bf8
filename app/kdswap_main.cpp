// kdswap: command-line entry. Parses the subcommand, runs it, turns errors into one line + exit 2.
#include <cstdio>
#include <exception>

#include <CLI/CLI.hpp>

#include "app/commands.h"
#include "core/util/error.h"
#include "core/util/memory.h"

int main(int argc, char** argv) {
  kdswap::useOneMallocArena();  // before any thread allocates (core/util/memory.h)
  CLI::App app{
      "kdswap: data-distributed parallel volume rendering with binary-swap compositing\n"
      "(Ma, Painter, Hansen & Krogh 1993), on P virtual nodes in one process.\n"};
  app.require_subcommand(1);
  kdswap::addRenderCommand(app);
  kdswap::addAnimateCommand(app);
  kdswap::addBenchCommand(app);
  kdswap::addInfoCommand(app);
  kdswap::addExportCommand(app);
  app.footer("Run 'kdswap SUBCOMMAND --help' for the options of each subcommand.");
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "kdswap: %s\n", e.what());
    return 2;
  } catch (const kdswap::CommandExit& e) {
    return e.code;
  } catch (const kdswap::Error& e) {
    std::fprintf(stderr, "kdswap: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "kdswap: unexpected error: %s\n", e.what());
    return 2;
  }
  return 0;
}
