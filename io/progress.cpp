#include "io/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

#include "io/interrupt.hpp"

namespace makeway::io {

ProgressBar::ProgressBar(std::string label, std::size_t total)
    : label_(std::move(label)),
      total_(std::max<std::size_t>(total, 1)),
      tty_(isatty(STDERR_FILENO) != 0),
      start_(std::chrono::steady_clock::now()) {}

void ProgressBar::update(std::size_t done, const std::string& note) {
    throw_if_interrupted();
    const double frac = std::min(1.0, static_cast<double>(done) / static_cast<double>(total_));
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const double eta = frac > 0 ? elapsed * (1 - frac) / frac : 0.0;
    if (tty_) {
        constexpr int kWidth = 30;
        const int filled = static_cast<int>(frac * kWidth);
        std::fprintf(stderr, "\r%s [%.*s%*s] %zu/%zu %3.0f%% eta %.0fs %s\033[K", label_.c_str(),
                     filled, "##############################", kWidth - filled, "", done, total_,
                     100 * frac, eta, note.c_str());
        std::fflush(stderr);
        drawn_ = true;
        return;
    }
    const int decile = static_cast<int>(frac * 10);
    if (decile == last_decile_) return;
    last_decile_ = decile;
    std::fprintf(stdout, "%s: %zu/%zu (%.0f%%) %.1fs %s\n", label_.c_str(), done, total_,
                 100 * frac, elapsed, note.c_str());
    std::fflush(stdout);
}

void ProgressBar::finish(const std::string& note) {
    update(total_, note);
    if (tty_) std::fputc('\n', stderr);
    drawn_ = false;
}

ProgressBar::~ProgressBar() {
    if (drawn_) std::fputs("\r\033[K", stderr);
}

}  // namespace makeway::io
