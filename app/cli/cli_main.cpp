// mostyle-cli: batch commands on BVH takes. Exit 0 on success, 1 on bad input (one line on
// stderr: "mostyle: FILE:LINE: what is wrong"), 2 on bad usage.
#include <CLI/CLI.hpp>
#include <functional>
#include <iostream>

#include "app/cli/cli_batch_commands.h"
#include "app/cli/cli_clip_commands.h"
#include "app/cli/cli_grid_command.h"
#include "app/cli/cli_synthesis_commands.h"
#include "app/cli/cli_pipeline_commands.h"
#include "app/cli/live_commands.h"
#include "engine/base/error.h"

int main(int argc, char** argv) {
  CLI::App app{"mostyle-cli: BVH takes, DTW alignment, sparse-coding style decomposition and blending"};
  app.require_subcommand(1);
  std::function<int()> run;
  mostyle::cli::add_info_command(app, &run);
  mostyle::cli::add_fk_command(app, &run);
  mostyle::cli::add_convert_command(app, &run);
  mostyle::cli::add_dtw_command(app, &run);
  mostyle::cli::add_align_command(app, &run);
  mostyle::cli::add_decompose_command(app, &run);
  mostyle::cli::add_blend_command(app, &run);
  mostyle::cli::add_mix_command(app, &run);
  mostyle::cli::add_transfer_command(app, &run);
  mostyle::cli::add_batch_command(app, &run);
  mostyle::cli::add_grid_command(app, &run);
  mostyle::cli::add_live_command(app, &run);
  mostyle::cli::add_live_send_command(app, &run);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return 2;
  }
  try {
    return run ? run() : 2;
  } catch (const mostyle::InputError& e) {
    std::cerr << "mostyle: " << e.what() << "\n";
    return 1;
  } catch (const std::bad_alloc&) {
    std::cerr << "mostyle: out of memory\n";
    return 1;
  } catch (const std::exception& e) {
    // Our own bug, not the input's; still one line and no abort.
    std::cerr << "mostyle: internal error: " << e.what() << "\n";
    return 1;
  }
}
