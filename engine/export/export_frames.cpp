#include "engine/export/export_frames.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "engine/base/error.h"
#include "engine/kinematics/sample_rows.h"

namespace mostyle {
namespace {

// A sample time this close to a working frame (in frames) takes that frame's values as they
// are: an export at the working rate writes the blend's own frames, not re-interpolated ones.
constexpr double kOnFrame = 1e-9;

std::string format(const char* pattern, double x, double y = 0.0, double z = 0.0) {
  char text[256];
  std::snprintf(text, sizeof text, pattern, x, y, z);
  return text;
}

void check_rate(double fps, const char* what) {
  if (!std::isfinite(fps) || fps <= 0.0 || fps > kMaxExportFps)
    throw InputError(std::string("export: the ") + what +
                     format(" must be a number of frames per second above 0 and at most %g, got %g.", kMaxExportFps, fps));
}

void check_motion(const Eigen::MatrixXd& world, const Eigen::VectorXd& at) {
  if (world.rows() == 0) throw InputError("export: the motion has no frames to export.");
  if (at.size() != world.rows())
    throw InputError(format("export: %g frames of positions but %g source frames; they must match.",
                            static_cast<double>(world.rows()), static_cast<double>(at.size())));
}

// world and at at fractional working rows `rows` (each within [0, F - 1] or, for a loop's
// seam, up to the extra row the caller appended). Rows that land on a frame copy it exactly:
// sample_rows reaches the last row as the one before plus the whole step, which may round.
ExportFrames sample(const Eigen::MatrixXd& world, const Eigen::VectorXd& at, Eigen::VectorXd rows, double fps) {
  const Eigen::Index last = world.rows() - 1;
  for (Eigen::Index k = 0; k < rows.size(); ++k) {
    const double nearest = std::round(rows[k]);
    if (std::abs(rows[k] - nearest) < kOnFrame) rows[k] = nearest;
    rows[k] = std::clamp(rows[k], 0.0, static_cast<double>(last));
  }
  ExportFrames out;
  out.fps = fps;
  sample_rows(world, rows, out.world);
  const Eigen::MatrixXd at_column = at;  // F x 1: sample_rows takes matrices
  Eigen::MatrixXd at_out;
  sample_rows(at_column, rows, at_out);
  out.at = at_out.col(0);
  for (Eigen::Index k = 0; k < rows.size(); ++k) {
    if (rows[k] != std::floor(rows[k])) continue;
    const Eigen::Index row = static_cast<Eigen::Index>(rows[k]);
    out.world.row(k) = world.row(row);
    out.at[k] = at[row];
  }
  return out;
}

}  // namespace

double motion_length_s(Eigen::Index frames, double fps) {
  return frames > 1 && fps > 0.0 ? static_cast<double>(frames - 1) / fps : 0.0;
}

int export_frame_count(double first_s, double last_s, double fps) {
  return static_cast<int>(std::floor((last_s - first_s) * fps + kExportTimeTolerance)) + 1;
}

ExportFrames export_frames(const Eigen::MatrixXd& world, const Eigen::VectorXd& at, double working_fps,
                           double out_fps, double first_s, double last_s) {
  check_rate(working_fps, "blend's frame rate");
  check_rate(out_fps, "output frame rate");
  check_motion(world, at);
  if (!std::isfinite(first_s) || !std::isfinite(last_s))
    throw InputError(format("export: the range must be two times in seconds, got %g s to %g s.", first_s, last_s));
  const double length = motion_length_s(world.rows(), working_fps);
  const double tolerance = kExportTimeTolerance / working_fps;
  if (first_s > last_s + tolerance)
    throw InputError(format("export: the range from %g s to %g s is empty: it starts after it ends.", first_s, last_s));
  if (first_s < -tolerance || last_s > length + tolerance)
    throw InputError(format("export: the range from %g s to %g s is outside the blend, which runs from 0 s to %g s.",
                            first_s, last_s, length));
  const double first = std::clamp(first_s, 0.0, length);
  const double last = std::clamp(last_s, first, length);
  const int count = export_frame_count(first, last, out_fps);
  Eigen::VectorXd rows(count);
  for (int k = 0; k < count; ++k) rows[k] = (first + k / out_fps) * working_fps;
  return sample(world, at, std::move(rows), out_fps);
}

ExportFrames export_loop_frames(const Eigen::MatrixXd& world, const Eigen::VectorXd& at, double working_fps,
                                double out_fps, const Eigen::Vector2d& travel) {
  check_rate(working_fps, "blend's frame rate");
  check_rate(out_fps, "output frame rate");
  check_motion(world, at);
  if (world.cols() % 3 != 0)
    throw InputError(format("export: positions need three columns per joint, got %g columns.",
                            static_cast<double>(world.cols())));
  const Eigen::Index n = world.rows();
  // One row more: the first frame again, where the next repeat of the loop has carried it.
  Eigen::MatrixXd closed(n + 1, world.cols());
  closed.topRows(n) = world;
  closed.row(n) = world.row(0);
  for (Eigen::Index c = 0; c < world.cols(); c += 3) {
    closed(n, c) += travel.x();
    closed(n, c + 2) += travel.y();
  }
  // A's frame does not wrap (the loop is cut from A's motion): it goes on at the last step's pace.
  Eigen::VectorXd closed_at(n + 1);
  closed_at.head(n) = at;
  closed_at[n] = n >= 2 ? 2.0 * at[n - 1] - at[n - 2] : at[0];
  const int count = std::max(1, static_cast<int>(std::lround(static_cast<double>(n) * out_fps / working_fps)));
  Eigen::VectorXd rows(count);
  for (int k = 0; k < count; ++k) rows[k] = static_cast<double>(k) * static_cast<double>(n) / count;
  return sample(closed, closed_at, std::move(rows), out_fps);
}

}  // namespace mostyle
