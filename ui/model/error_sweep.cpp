#include "ui/model/error_sweep.h"

#include <algorithm>
#include <iterator>

namespace mostyle::ui {

void ErrorSweep::insert(const ErrorPoint& point, bool replace) {
  auto same = [&](const ErrorPoint& e) {
    return e.components == point.components && e.sparsity == point.sparsity && e.mode == point.mode;
  };
  if (replace) curve_.erase(std::remove_if(curve_.begin(), curve_.end(), same), curve_.end());
  else if (std::find_if(curve_.begin(), curve_.end(), same) != curve_.end()) return;
  curve_.push_back(point);
  std::sort(curve_.begin(), curve_.end(), [](const ErrorPoint& a, const ErrorPoint& b) { return a.components < b.components; });
}

void ErrorSweep::add(const Decomposed& d, const PreparedTakes* takes, const std::vector<std::string>& paths,
                     const PrepareOptions& options) {
  insert(ErrorPoint{d.params.components, d.params.sparsity, d.params.mode, d.rmse}, true);
  const bool same_curve = params_.mode == d.params.mode && params_.sparsity == d.params.sparsity &&
                          params_.basic_motions == d.params.basic_motions;
  if (same_curve && worker_ && swept_ == takes) return;
  swept_ = takes;
  start(d.params, paths, options);
}

void ErrorSweep::start(const DecomposeParams& base, const std::vector<std::string>& paths, const PrepareOptions& options) {
  params_ = base;
  params_.components = kComponents[0];
  next_ = 0;
  worker_ = std::make_unique<Worker>(read_);  // the previous one (if any) is cancelled and joined
  seen_version_ = 0;
  if (wake_) worker_->set_on_change(wake_);
  worker_->decompose(params_);
  worker_->load(paths, options);
}

void ErrorSweep::set_wake(std::function<void()> wake) {
  wake_ = std::move(wake);
  if (worker_) worker_->set_on_change(wake_);
}

bool ErrorSweep::has_news() const { return next_ >= 0 && worker_ && worker_->snapshot()->version != seen_version_; }

void ErrorSweep::poll() {
  if (next_ < 0 || !worker_) return;
  auto snap = worker_->snapshot();
  seen_version_ = snap->version;
  if (!snap->error.empty()) {  // e.g. k larger than the channels: the sweep stops there
    next_ = -1;
    return;
  }
  const Decomposed* d = snap->decomposed.get();
  if (d == nullptr || d->params.components != params_.components) return;
  insert(ErrorPoint{d->params.components, d->params.sparsity, d->params.mode, d->rmse}, false);
  if (++next_ >= static_cast<int>(std::size(kComponents))) {
    next_ = -1;
    return;
  }
  params_.components = kComponents[next_];
  worker_->decompose(params_);
}

void ErrorSweep::wait_idle() {
  while (next_ >= 0 && worker_) {  // each step's next request is made by poll
    worker_->wait_idle();
    poll();
  }
}

}  // namespace mostyle::ui
