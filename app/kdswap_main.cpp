// kdswap: command-line entry. Parses the subcommand, runs it, turns errors into one line + exit 2.
#include <cstdio>
#include <exception>
#include <string>

#include <CLI/CLI.hpp>

#include "app/commands.h"
#include "core/util/error.h"
#include "core/util/memory.h"
#include "core/util/printable_text.h"

using kdswap::oneLine;

int main(int argc, char** argv) {
  kdswap::configureMalloc();  // before any thread allocates (core/util/memory.h)
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
  // CLI11 would report an unknown first word, or none, as "A subcommand is required".
  const std::string first = argc > 1 ? argv[1] : "";
  std::string names;
  bool known = false;
  const CLI::App& all = app;  // the const overload: every subcommand, not only the parsed ones
  for (const CLI::App* sub : all.get_subcommands([](const CLI::App*) { return true; })) {
    known = known || sub->get_name() == first;
    names += (names.empty() ? "" : ", ") + sub->get_name();
  }
  const bool help = first == "-h" || first == "--help";
  if (argc == 1 || (first[0] == '-' && !help)) {  // options come after the subcommand
    const std::string before = argc == 1 ? "" : " before \"" + oneLine(first) + "\"";
    std::fprintf(stderr, "kdswap: give a subcommand%s, one of %s (kdswap --help explains them; kdswap render draws "
                 "the default scene)\n", before.c_str(), names.c_str());
    return 2;
  }
  if (!help && !known) {
    std::fprintf(stderr, "kdswap: unknown subcommand \"%s\" (expected one of %s)\n", oneLine(first).c_str(), names.c_str());
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "kdswap: %s\n", oneLine(e.what()).c_str());
    return 2;
  } catch (const kdswap::CommandExit& e) {
    return e.code;
  } catch (const kdswap::Error& e) {
    std::fprintf(stderr, "kdswap: %s\n", oneLine(e.what()).c_str());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "kdswap: unexpected error: %s\n", oneLine(e.what()).c_str());
    return 2;
  }
  return 0;
}
