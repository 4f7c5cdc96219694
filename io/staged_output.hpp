#pragma once
// All-or-nothing outputs for commands that write several files, and marked-incomplete folders for
// long recordings.
//
// StagedOutput: everything is written under staging(), a hidden folder on the target's file
// system: beside a target that does not exist yet (commit() is then one rename), inside an
// existing one (commit() renames file by file, replacing files of the same name; other files
// stay). Destroyed without commit() (an error, an interrupt) the staging folder is removed and
// the target is left as it was.
//
// RecordingFolder: a recording of hours cannot be staged (the disk may hold it once, not twice),
// so it is written in place with a PARTIAL marker first and summary.json last. A run that stops
// early leaves the marker and a summary with "complete": false saying how far it got.
#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "io/interrupt.hpp"
#include "io/json_io.hpp"

namespace makeway::io {

class StagedOutput {
  public:
    /// `target`: the folder (or, with a file name, the folder holding the files) being produced.
    explicit StagedOutput(std::filesystem::path target);
    ~StagedOutput();
    StagedOutput(const StagedOutput&) = delete;
    StagedOutput& operator=(const StagedOutput&) = delete;

    /// Where to write: staging() / "run.json" ends up as target / "run.json".
    const std::filesystem::path& staging() const { return staging_; }
    const std::filesystem::path& target() const { return target_; }

    /// Checks for an interrupt, then moves everything into place. Throws FileError or Interrupted
    /// (the staging folder is then removed by the destructor).
    void commit();

  private:
    std::filesystem::path target_, staging_;
    bool inside_ = false;
    DeferInterrupts defer_;
};

class RecordingFolder {
  public:
    /// Creates `folder`, removes an earlier summary.json and writes the PARTIAL marker.
    RecordingFolder(std::filesystem::path folder, const std::string& command);
    RecordingFolder(const RecordingFolder&) = delete;
    RecordingFolder& operator=(const RecordingFolder&) = delete;

    const std::filesystem::path& path() const { return folder_; }
    /// summary.json with "complete": true, then the marker removed.
    void complete(Json summary);
    /// summary.json with "complete": false and "stopped": why; the marker says why too. Never
    /// throws.
    void stopped(Json summary_so_far, const std::string& why) noexcept;

  private:
    std::filesystem::path folder_;
    DeferInterrupts defer_;
};

/// Refuses an output that is one of the command's inputs: FileError naming the output when it is
/// the same file or folder as an input (through symbolic or hard links included). Pairs are
/// (option, path); outputs that do not exist yet pass. Then protects the inputs: a StagedOutput
/// whose commit would replace one of them refuses before anything moves.
void refuse_outputs_over_inputs(const std::vector<std::pair<std::string, std::string>>& outputs,
                                const std::vector<std::pair<std::string, std::string>>& inputs);
/// Only the protection (tests; refuse_outputs_over_inputs sets it).
void protect_inputs(const std::vector<std::pair<std::string, std::string>>& inputs);

/// `path` as the user knows it: a path inside a live staging folder becomes the path it will have
/// after the commit (FileError names files this way).
std::string shown_path(const std::string& path);

/// Throws FileError(path) when the file system holding `path` has less than `bytes` (plus 5 %)
/// available; `what` names the work ("100000 frames").
void check_free_space(const std::filesystem::path& path, std::uintmax_t bytes,
                      const std::string& what);

}  // namespace makeway::io
