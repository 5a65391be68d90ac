#pragma once
// mostyle-cli subcommands over many takes: batch (runs a JOBS file of commands, sharded across
// machines) and grid (writes a JOBS file of blends).
#include <CLI/CLI.hpp>
#include <functional>

namespace mostyle::cli {

// Each adds its subcommand to `app` and sets *run to the action to take when it was chosen.
void add_batch_command(CLI::App& app, std::function<int()>* run);
void add_grid_command(CLI::App& app, std::function<int()>* run);

}  // namespace mostyle::cli
