#include "io/error.hpp"

#include <iostream>

#include "io/staged_output.hpp"

namespace makeway::io {

FileError::FileError(const std::string& path, const std::string& problem)
    : std::runtime_error(shown_path(path) + ": " + problem),
      path_(shown_path(path)),
      problem_(problem) {}

void print_warning(const std::string& message) {
    std::cerr << "makeway: warning: " << message << "\n";
}

}  // namespace makeway::io
