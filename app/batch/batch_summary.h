#pragma once
// What `mostyle-cli batch` records of its jobs: one record per job, in the summary written at
// the end and, as each job finishes, in a journal beside it, so that a shard killed part way
// (a scheduler's time limit, SIGKILL) keeps the records of every job that had finished.
//
// Why a journal rather than the summary rewritten after every job: appending one line costs the
// same for the first job and the ten-thousandth, where a rewrite costs the whole summary each
// time (a shard of 10,000 jobs would write some 15 GB and sync 10,000 files to keep a 3 MB
// summary current). A record is appended with one write(2) to a file opened O_APPEND, which the
// kernel holds once the call returns, so killing the process never cuts it; only a crash of the
// machine can lose the last lines.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "app/batch/job_runner.h"

namespace mostyle::cli {

enum class JobStatus { kOk, kFailed, kSkipped };

// {"line", "args", "status": "ok"|"failed"|"skipped", "error", "seconds", "attempts",
// "max_rss_mb"}. line: in JOBS, from 1; attempts 0 for a job that was not run; max_rss_mb: the
// peak resident memory of its (last) process, MB.
nlohmann::ordered_json job_record(int line, const std::vector<std::string>& args, JobStatus status,
                                  const JobResult& result);

// The journal of a summary at SUMMARY: SUMMARY.journal.
std::string journal_path(const std::string& summary_path);

// A JSON-lines file of job records, one per line, in the order the jobs finished.
class SummaryJournal {
 public:
  // Creates `path`, or empties what an earlier run left there. Throws InputError
  // "PATH: cannot write: reason".
  explicit SummaryJournal(std::string path);
  ~SummaryJournal();
  SummaryJournal(const SummaryJournal&) = delete;
  SummaryJournal& operator=(const SummaryJournal&) = delete;

  // Appends one record as one line (invalid UTF-8 in it replaced). Never throws: the first
  // failure is kept as "PATH: cannot write: reason" in error().
  void append(const nlohmann::ordered_json& record);
  const std::string& error() const { return error_; }
  // Closes the file and removes it: the summary, once written, holds every record.
  void remove();

 private:
  std::string path_;
  int fd_ = -1;
  std::string error_;
};

}  // namespace mostyle::cli
