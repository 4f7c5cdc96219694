#include "io/error.hpp"

#include <iostream>

#include "io/staged_output.hpp"

namespace makeway::io {

FileError::FileError(const std::string& path, const std::string& problem)
    : std::runtime_error(shown_path(path) + ": " + problem),
      path_(shown_path(path)),
      problem_(problem) {}

std::optional<std::string> problem_after_path(const std::string& path, const std::string& message) {
    const std::string prefix = path + ": ";
    if (message.rfind(prefix, 0) != 0) return std::nullopt;
    return message.substr(prefix.size());
}

void print_warning(const std::string& message) {
    std::cerr << "makeway: warning: " << message << "\n";
}

}  // namespace makeway::io
