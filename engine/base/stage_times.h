#pragma once
// How long each stage of the chain took, wall time in milliseconds. A measure of a run, kept
// beside the stage values (the worker's snapshot, the CLI's report, the editor's metrics), never
// inside them: a stage value says what was made, not how long it took. Each stage function takes
// an optional StageTimes* and sets its own entries (prepare_takes: preprocess and dtw;
// decompose_takes: decompose; mix_palette: synthesize and postprocess); reading files (load) and
// writing them (export) are timed by whoever does them.
namespace mostyle {

struct StageTimes {
  double load_ms = 0, preprocess_ms = 0, dtw_ms = 0, decompose_ms = 0, synthesize_ms = 0,
         postprocess_ms = 0, export_ms = 0;
};

}  // namespace mostyle
