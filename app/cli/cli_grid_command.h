#pragma once
// mostyle-cli grid: writes a JOBS file for batch, one blend per ordered pair of takes and alpha,
// or (--transfer) one style transfer per content, style and strength.
#include <CLI/CLI.hpp>
#include <functional>

namespace mostyle::cli {

// Adds the subcommand to `app` and sets *run to the action to take when it was chosen.
void add_grid_command(CLI::App& app, std::function<int()>* run);

}  // namespace mostyle::cli
