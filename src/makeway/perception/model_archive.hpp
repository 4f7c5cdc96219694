#pragma once
// The container check in front of libtorch's model reader. torch trusts the archive it is given:
// a damaged file can make it allocate tens of gigabytes or crash (found by the mutation test in
// tests/perception). A model file is a ZIP archive of stored records with CRC-32s, so before torch
// sees it we check, through libzip, that the archive is consistent, that every record's size
// fits the file and that every record reads back with its CRC; torch then only sees bytes it wrote.
#include <filesystem>
#include <string>
#include <string_view>

namespace makeway::perception {

/// Empty when `bytes` is a sound model archive (consistent ZIP, records within the file, CRCs
/// right, a data.pkl record present); else what is wrong, one line.
std::string model_archive_problem(std::string_view bytes);

/// The bytes of a model file that passed model_archive_problem(); throws std::runtime_error
/// "PATH: no such KIND file", "PATH: cannot read the KIND file" or "PATH: <the problem>".
std::string read_checked_model_archive(const std::filesystem::path& path, const std::string& kind);

/// The first non-empty line of a library's message, at most 120 characters (error lines are one
/// line).
std::string first_line(const std::string& text);

}  // namespace makeway::perception
