#pragma once
// mostyle-cli subcommands on one clip: info, fk, convert.
#include <CLI/CLI.hpp>
#include <functional>

namespace mostyle::cli {

// Each adds its subcommand to `app` and sets *run to the action to take when it was chosen.
void add_info_command(CLI::App& app, std::function<int()>* run);
void add_fk_command(CLI::App& app, std::function<int()>* run);
void add_convert_command(CLI::App& app, std::function<int()>* run);

}  // namespace mostyle::cli
