#pragma once
// A progress bar for long work. On a terminal it redraws one line of stderr, erased again when the
// work stops before finish() (an error then stands alone on its line); elsewhere (CI logs, files)
// it prints a line at every 10 % to stdout, so that stderr holds only warnings and the error.
#include <chrono>
#include <cstddef>
#include <string>

namespace makeway::io {

class ProgressBar {
  public:
    ProgressBar(std::string label, std::size_t total);
    ~ProgressBar();  ///< erases an unfinished terminal line
    ProgressBar(const ProgressBar&) = delete;
    ProgressBar& operator=(const ProgressBar&) = delete;
    /// Marks `done` items finished; `note` is shown after the bar (e.g. "12.3 M rays/s"). Long work
    /// calls this often, so it is also where a deferred Ctrl-C is noticed: throws Interrupted.
    void update(std::size_t done, const std::string& note = "");
    /// Completes the line.
    void finish(const std::string& note = "");

  private:
    std::string label_;
    std::size_t total_;
    bool tty_;
    bool drawn_ = false;  ///< a terminal line is showing
    int last_decile_ = -1;
    std::chrono::steady_clock::time_point start_;
};

}  // namespace makeway::io
