#include "io/staged_output.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <system_error>
#include <utility>
#include <vector>

#include "io/error.hpp"
#include "io/file_util.hpp"

namespace makeway::io {
namespace fs = std::filesystem;
namespace {

// "1.7 TB", "3.2 GB", "12.0 MB", "800 bytes": a nearly full disk is not "0.0 GB free".
std::string human_bytes(std::uintmax_t bytes) {
    const double b = static_cast<double>(bytes);
    char text[32];
    if (b >= 1e12)
        std::snprintf(text, sizeof(text), "%.1f TB", b / 1e12);
    else if (b >= 1e9)
        std::snprintf(text, sizeof(text), "%.1f GB", b / 1e9);
    else if (b >= 1e6)
        std::snprintf(text, sizeof(text), "%.1f MB", b / 1e6);
    else if (b >= 1e3)
        std::snprintf(text, sizeof(text), "%.1f kB", b / 1e3);
    else
        std::snprintf(text, sizeof(text), "%ju bytes", bytes);
    return text;
}

// The command's inputs (option, path), which no output may replace.
std::mutex g_inputs_mutex;
std::vector<std::pair<std::string, fs::path>> g_inputs;

// The input `path` is (the same file or folder, through any link), if any.
const std::pair<std::string, fs::path>* input_at(const fs::path& path) {
    std::error_code ec;
    if (!fs::exists(path, ec)) return nullptr;
    const std::lock_guard<std::mutex> lock(g_inputs_mutex);
    for (const auto& input : g_inputs) {
        if (fs::equivalent(path, input.second, ec)) return &input;
    }
    return nullptr;
}

// Throws when an entry of `from` cannot replace its namesake in `to` (a folder where a file goes,
// or the reverse): checked for everything before anything moves.
void check_moves(const fs::path& from, const fs::path& to) {
    for (const auto& entry : fs::directory_iterator(from)) {
        const fs::path dest = to / entry.path().filename();
        std::error_code ec;
        const fs::file_status st = fs::symlink_status(dest, ec);
        if (!fs::exists(st)) continue;
        if (const auto* input = input_at(dest)) {
            throw FileError(dest.string(), "is this command's input " + input->first +
                                               ": an output would replace it");
        }
        if (entry.is_directory() && fs::is_directory(st)) {
            check_moves(entry.path(), dest);
        } else if (entry.is_directory() || fs::is_directory(st)) {
            throw FileError(dest.string(),
                            "in the way of an output (a folder where a file goes, or the reverse)");
        }
    }
}

// Moves every entry of `from` into `to` (which exists), replacing files, merging folders.
void move_into(const fs::path& from, const fs::path& to) {
    for (const auto& entry : fs::directory_iterator(from)) {
        const fs::path dest = to / entry.path().filename();
        std::error_code ec;
        if (entry.is_directory() && fs::is_directory(fs::symlink_status(dest, ec))) {
            move_into(entry.path(), dest);
            continue;
        }
        fs::rename(entry.path(), dest, ec);
        if (ec) throw FileError(dest.string(), "cannot move into place: " + ec.message());
    }
}

// mkdtemp makes 0700 folders; outputs get the permissions any new folder would (0777 - umask).
void open_up(const fs::path& folder) {
    const mode_t mask = ::umask(0);
    ::umask(mask);
    ::chmod(folder.c_str(), 0777 & ~mask);
}

// Live staging folders and their targets, for shown_path.
std::mutex g_staging_mutex;
std::vector<std::pair<std::string, std::string>> g_stagings;

}  // namespace

std::string shown_path(const std::string& path) {
    const std::lock_guard<std::mutex> lock(g_staging_mutex);
    for (const auto& [staging, target] : g_stagings) {
        if (path.compare(0, staging.size(), staging) == 0 &&
            (path.size() == staging.size() || path[staging.size()] == '/')) {
            return target + path.substr(staging.size());
        }
    }
    return path;
}

StagedOutput::StagedOutput(fs::path target)
    : target_(fs::path(std::move(target)).lexically_normal()) {
    if (target_.filename().empty()) target_ = target_.parent_path();  // "out/" -> "out"
    if (target_.empty()) target_ = ".";
    std::error_code ec;
    std::string tmpl;
    if (fs::exists(fs::symlink_status(target_, ec)) || fs::exists(target_, ec)) {
        // An existing folder ("." included): stage inside it, so the files move within one folder.
        if (!fs::is_directory(target_, ec))
            throw FileError(target_.string(), "exists and is not a folder");
        tmpl = (target_ / ".makeway-staging.XXXXXX").string();
        inside_ = true;
    } else {
        fs::path parent = target_.parent_path();
        if (parent.empty()) parent = ".";
        fs::create_directories(parent, ec);
        if (ec) throw FileError(target_.string(), "cannot create folder: " + ec.message());
        tmpl = (parent / ("." + target_.filename().string() + ".staging.XXXXXX")).string();
    }
    if (::mkdtemp(tmpl.data()) == nullptr) {
        throw FileError(target_.string(),
                        std::string("cannot create a staging folder: ") + std::strerror(errno));
    }
    staging_ = tmpl;
    open_up(staging_);
    const std::lock_guard<std::mutex> lock(g_staging_mutex);
    g_stagings.emplace_back(staging_.string(), target_.string());
}

StagedOutput::~StagedOutput() {
    {
        const std::lock_guard<std::mutex> lock(g_staging_mutex);
        std::erase(g_stagings, std::pair(staging_.string(), target_.string()));
    }
    std::error_code ec;
    fs::remove_all(staging_, ec);
}

void StagedOutput::commit() {
    throw_if_interrupted();
    std::error_code ec;
    if (!inside_) {
        fs::rename(staging_, target_, ec);
        if (!ec) return;
        fs::create_directories(target_, ec);  // the target appeared meanwhile
        if (ec) throw FileError(target_.string(), "cannot create folder: " + ec.message());
    }
    check_moves(staging_, target_);
    move_into(staging_, target_);
}

RecordingFolder::RecordingFolder(fs::path folder, const std::string& command)
    : folder_(std::move(folder)) {
    std::error_code ec;
    fs::create_directories(folder_, ec);
    if (ec) throw FileError(folder_.string(), "cannot create folder: " + ec.message());
    fs::remove(folder_ / "summary.json", ec);
    if (ec)
        throw FileError((folder_ / "summary.json").string(),
                        "cannot remove the earlier summary: " + ec.message());
    write_file_atomic(
        folder_ / "PARTIAL",
        "makeway " + command +
            " is writing this folder or stopped before the end; summary.json says how "
            "far it got\n");
}

void RecordingFolder::complete(Json summary) {
    summary["complete"] = true;
    write_json(folder_ / "summary.json", summary);
    std::error_code ec;
    fs::remove(folder_ / "PARTIAL", ec);
}

void RecordingFolder::stopped(Json summary, const std::string& why) noexcept {
    // Each write may throw Interrupted after it landed (the flag is still set): the last word is
    // written all the same.
    try {
        summary["complete"] = false;
        summary["stopped"] = why;
        write_json(folder_ / "summary.json", summary);
    } catch (...) {
    }
    try {
        write_file_atomic(folder_ / "PARTIAL", "makeway stopped before the end: " + why +
                                                   "; summary.json says how far it got\n");
    } catch (...) {
    }
}

void protect_inputs(const std::vector<std::pair<std::string, std::string>>& inputs) {
    const std::lock_guard<std::mutex> lock(g_inputs_mutex);
    g_inputs.clear();
    for (const auto& [option, path] : inputs) g_inputs.emplace_back(option, path);
}

void refuse_outputs_over_inputs(const std::vector<std::pair<std::string, std::string>>& outputs,
                                const std::vector<std::pair<std::string, std::string>>& inputs) {
    for (const auto& [out_option, out] : outputs) {
        std::error_code ec;
        if (out.empty() || !fs::exists(out, ec)) continue;
        for (const auto& [in_option, in] : inputs) {
            if (fs::equivalent(out, in, ec)) {
                throw FileError(
                    out, out_option + " names the input given as " + in_option +
                             (fs::path(out).lexically_normal() == fs::path(in).lexically_normal()
                                  ? ""
                                  : " (the same file through a link)") +
                             ": choose another output");
            }
        }
    }
    protect_inputs(inputs);
}

void check_free_space(const fs::path& path, std::uintmax_t bytes, const std::string& what) {
    fs::path probe = path;
    std::error_code ec;
    while (!probe.empty() && !fs::exists(probe, ec)) probe = probe.parent_path();
    if (probe.empty()) probe = ".";
    const fs::space_info space = fs::space(probe, ec);
    if (ec) return;  // unknown: nothing to check against
    const std::uintmax_t need = bytes + bytes / 20;
    if (space.available < need) {
        throw FileError(path.string(), what + " need about " + human_bytes(need) + " but " +
                                           human_bytes(space.available) + " are free there");
    }
}

}  // namespace makeway::io
