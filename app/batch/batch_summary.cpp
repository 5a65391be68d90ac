#include "app/batch/batch_summary.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "engine/base/error.h"

namespace mostyle::cli {

using Json = nlohmann::ordered_json;

Json job_record(int line, const std::vector<std::string>& args, JobStatus status, const JobResult& result) {
  Json record;
  record["line"] = line;
  record["args"] = args;
  record["status"] = status == JobStatus::kOk ? "ok" : status == JobStatus::kFailed ? "failed" : "skipped";
  record["error"] = result.error;
  record["seconds"] = result.seconds;
  record["attempts"] = result.attempts;
  record["max_rss_mb"] = result.max_rss_mb;
  return record;
}

std::string journal_path(const std::string& summary_path) { return summary_path + ".journal"; }

SummaryJournal::SummaryJournal(std::string path) : path_(std::move(path)) {
  fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_APPEND | O_CLOEXEC, 0644);
  if (fd_ < 0) throw InputError(path_ + ": cannot write: " + std::strerror(errno));
}

SummaryJournal::~SummaryJournal() {
  if (fd_ >= 0) ::close(fd_);
}

void SummaryJournal::append(const Json& record) {
  if (fd_ < 0 || !error_.empty()) return;
  // Messages quote file contents (joint names): invalid UTF-8 is replaced, not thrown on.
  const std::string line = record.dump(-1, ' ', false, Json::error_handler_t::replace) + "\n";
  size_t done = 0;
  while (done < line.size()) {
    const ssize_t n = ::write(fd_, line.data() + done, line.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      error_ = path_ + ": cannot write: " + std::strerror(n < 0 ? errno : EIO);
      return;
    }
    done += static_cast<size_t>(n);
  }
}

void SummaryJournal::remove() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  ::unlink(path_.c_str());
}

}  // namespace mostyle::cli
