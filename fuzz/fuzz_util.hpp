#pragma once
// What the fuzz targets that go through files share: a private folder (removed at exit) and the
// split of one input into two files at its first NUL byte.
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>

namespace makeway::fuzz {

/// A folder of this process's own under the temporary folder, removed at exit.
inline const std::filesystem::path& private_dir() {
    static const std::filesystem::path dir = [] {
        std::string tmpl =
            (std::filesystem::temp_directory_path() / "makeway_fuzz.XXXXXX").string();
        if (!::mkdtemp(tmpl.data())) std::abort();
        std::atexit([] {
            std::error_code ec;
            std::filesystem::remove_all(private_dir(), ec);
        });
        return std::filesystem::path(tmpl);
    }();
    return dir;
}

/// The bytes before the first NUL and the bytes after it (empty when there is none).
inline std::pair<std::string_view, std::string_view> split_at_nul(const std::uint8_t* data,
                                                                  std::size_t size) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    const std::size_t cut = bytes.find('\0');
    if (cut == std::string_view::npos) return {bytes, {}};
    return {bytes.substr(0, cut), bytes.substr(cut + 1)};
}

}  // namespace makeway::fuzz
