#include "io/error.hpp"

#include "io/staged_output.hpp"

namespace makeway::io {

FileError::FileError(const std::string& path, const std::string& problem)
    : std::runtime_error(shown_path(path) + ": " + problem), path_(shown_path(path)), problem_(problem) {}

}  // namespace makeway::io
