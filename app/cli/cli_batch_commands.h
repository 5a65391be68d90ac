#pragma once
// mostyle-cli batch: runs a JOBS file of commands, several at a time, sharded across machines.
#include <CLI/CLI.hpp>
#include <functional>

namespace mostyle::cli {

// Adds the subcommand to `app` and sets *run to the action to take when it was chosen.
void add_batch_command(CLI::App& app, std::function<int()>* run);

}  // namespace mostyle::cli
