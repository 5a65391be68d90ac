#pragma once
// mostyle-cli subcommands that look at the stages before the synthesis: dtw, align, decompose
// (blend, mix and transfer are in cli_synthesis_commands.h).
#include <CLI/CLI.hpp>
#include <functional>

namespace mostyle::cli {

void add_dtw_command(CLI::App& app, std::function<int()>* run);
void add_align_command(CLI::App& app, std::function<int()>* run);
void add_decompose_command(CLI::App& app, std::function<int()>* run);

}  // namespace mostyle::cli
