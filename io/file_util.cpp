#include "io/file_util.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <system_error>

#include "io/error.hpp"
#include "io/interrupt.hpp"

namespace makeway::io {
namespace fs = std::filesystem;

std::string read_file(const fs::path& path, bool allow_empty, std::size_t max_bytes) {
    std::error_code ec;
    const auto status = fs::status(path, ec);
    if (ec || !fs::exists(status)) throw FileError(path.string(), "no such file");
    if (fs::is_directory(status)) throw FileError(path.string(), "is a folder, not a file");
    // Opening a FIFO blocks until something writes to it, possibly forever.
    if (!fs::is_regular_file(status))
        throw FileError(path.string(), "not a regular file (a FIFO, device or socket)");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw FileError(path.string(), std::string("cannot open: ") + std::strerror(errno));
    in.seekg(0, std::ios::end);
    const std::streamoff size = in.tellg();
    if (size < 0) throw FileError(path.string(), "cannot determine the file size");
    if (static_cast<std::size_t>(size) > max_bytes) {
        throw FileError(path.string(), "file too large (" + std::to_string(size) + " bytes)");
    }
    if (size == 0 && !allow_empty) throw FileError(path.string(), "empty file");
    std::string data(static_cast<std::size_t>(size), '\0');
    in.seekg(0);
    in.read(data.data(), size);
    if (!in) throw FileError(path.string(), "read failed");
    return data;
}

namespace {

void write_file_atomic_now(const fs::path& path, std::string_view data) {
    std::error_code ec;
    const fs::path parent = path.parent_path();
    if (!parent.empty()) {
        fs::create_directories(parent, ec);
        if (ec) throw FileError(path.string(), "cannot create folder: " + ec.message());
    }
    std::string tmpl = path.string() + ".tmp.XXXXXX";
    const int fd = ::mkstemp(tmpl.data());
    if (fd < 0)
        throw FileError(path.string(), std::string("cannot write: ") + std::strerror(errno));
    const char* p = data.data();
    std::size_t left = data.size();
    while (left > 0) {
        const ssize_t n = ::write(fd, p, left);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            const std::string why = std::strerror(errno);
            ::close(fd);
            ::unlink(tmpl.c_str());
            throw FileError(path.string(), "write failed: " + why);
        }
        p += n;
        left -= static_cast<std::size_t>(n);
    }
    ::fchmod(fd, 0644);
    if (::close(fd) != 0) {
        ::unlink(tmpl.c_str());
        throw FileError(path.string(), "write failed on close");
    }
    if (::rename(tmpl.c_str(), path.c_str()) != 0) {
        const std::string why = std::strerror(errno);
        ::unlink(tmpl.c_str());
        throw FileError(path.string(), "cannot replace file: " + why);
    }
}

}  // namespace

void write_file_atomic(const fs::path& path, std::string_view data) {
    {
        // An interrupt between mkstemp and rename would leave the temporary file behind.
        const DeferInterrupts defer;
        write_file_atomic_now(path, data);
    }
    throw_if_interrupted();
}

std::string to_lower(std::string text) {
    std::transform(text.begin(), text.end(), text.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return text;
}

std::string frame_name(std::size_t index) {
    char buf[24];
    std::snprintf(buf, sizeof(buf), "%06zu", index);
    return buf;
}

std::string lower_extension(const fs::path& path) {
    std::string ext = path.extension().string();
    if (!ext.empty() && ext.front() == '.') ext.erase(0, 1);
    return to_lower(std::move(ext));
}

}  // namespace makeway::io
