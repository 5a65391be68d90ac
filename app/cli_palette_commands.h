#pragma once
// mostyle-cli subcommands of the style palette (issue #9): mix (2 to 16 takes with weights) and
// transfer (a style change put on a take of one's own).
#include <CLI/CLI.hpp>
#include <functional>

namespace mostyle::cli {

void add_mix_command(CLI::App& app, std::function<int()>* run);
void add_transfer_command(CLI::App& app, std::function<int()>* run);

}  // namespace mostyle::cli
