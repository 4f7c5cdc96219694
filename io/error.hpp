#pragma once
// The two error types of the io layer. Messages never end with a newline.
#include <optional>
#include <stdexcept>
#include <string>

namespace makeway::io {

/// A file's content is malformed: what is wrong, without the file name (parsers work on buffers).
class FormatError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

/// A named input or output file cannot be used. what() is "FILE: what is wrong".
class FileError : public std::runtime_error {
  public:
    /// A path inside a staging folder (io::StagedOutput) is named as the file it will become.
    FileError(const std::string& path, const std::string& problem);
    const std::string& path() const { return path_; }
    const std::string& problem() const { return problem_; }

  private:
    std::string path_;
    std::string problem_;
};

/// What a message that names `path` first ("PATH: what is wrong") says is wrong; nullopt when the
/// message does not start with the path (a loader's own errors name their file; others do not).
std::optional<std::string> problem_after_path(const std::string& path, const std::string& message);

/// "makeway: warning: MESSAGE" on stderr: input that is readable but suspicious (a mesh whose size
/// cannot be furniture of its class, fields a format cannot keep).
void print_warning(const std::string& message);

}  // namespace makeway::io
