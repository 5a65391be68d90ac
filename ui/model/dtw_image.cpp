#include "ui/model/dtw_image.h"

#include <algorithm>

namespace mostyle::ui {

DtwCostImage dtw_cost_image(const PreparedTakes& takes, int take) {
  DtwCostImage img;
  if (take < 1 || take >= takes.size()) return img;
  const Alignment& al = takes.takes[static_cast<size_t>(take)].alignment;
  const Eigen::MatrixXd& fa = al.feature.a;
  const Eigen::MatrixXd& fb = al.feature.b;
  if (fa.rows() == 0 || fb.rows() == 0) return img;
  img.frames_a = static_cast<int>(fa.rows());
  img.frames_b = static_cast<int>(fb.rows());
  img.rows = std::min(img.frames_a, DtwCostImage::kMaxCells);
  img.cols = std::min(img.frames_b, DtwCostImage::kMaxCells);
  img.cost.resize(img.rows, img.cols);
  for (int r = 0; r < img.rows; ++r) {
    const int i = std::min(img.frames_a - 1, static_cast<int>((r + 0.5) * img.frames_a / img.rows));
    for (int c = 0; c < img.cols; ++c) {
      const int j = std::min(img.frames_b - 1, static_cast<int>((c + 0.5) * img.frames_b / img.cols));
      img.cost(r, c) = static_cast<float>((fa.row(i) - fb.row(j)).norm());
    }
  }
  const float top = img.cost.maxCoeff();
  if (top > 0.0f) img.cost /= top;
  return img;
}

}  // namespace mostyle::ui
