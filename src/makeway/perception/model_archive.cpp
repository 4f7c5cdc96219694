#include "makeway/perception/model_archive.hpp"

#include <zip.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <memory>
#include <stdexcept>
#include <vector>

namespace makeway::perception {

std::string model_archive_problem(std::string_view bytes) {
    if (bytes.size() < 22) return "too short for a model archive";
    zip_error_t error;
    zip_error_init(&error);
    zip_source_t* source = zip_source_buffer_create(bytes.data(), bytes.size(), 0, &error);
    if (!source) {
        zip_error_fini(&error);
        return "cannot read the archive";
    }
    zip_t* archive = zip_open_from_source(source, ZIP_RDONLY | ZIP_CHECKCONS, &error);
    if (!archive) {
        std::string why = std::string("not a model archive (") + zip_error_strerror(&error) + ")";
        zip_source_free(source);
        zip_error_fini(&error);
        return why;
    }
    zip_error_fini(&error);
    const std::unique_ptr<zip_t, int (*)(zip_t*)> closer(archive, zip_close);
    const zip_int64_t entries = zip_get_num_entries(archive, 0);
    bool has_data = false;
    std::vector<char> buffer(1 << 16);
    for (zip_int64_t i = 0; i < entries; ++i) {
        zip_stat_t st;
        if (zip_stat_index(archive, static_cast<zip_uint64_t>(i), 0, &st) != 0)
            return "unreadable record " + std::to_string(i);
        const std::string name = st.name ? st.name : "";
        // torch writes records stored, not compressed: a record larger than the file is damage
        // (or a zip bomb), never a model.
        if (!(st.valid & ZIP_STAT_SIZE) || st.size > bytes.size())
            return "record '" + name + "' is larger than the file";
        if (name.size() >= 8 && name.compare(name.size() - 8, 8, "data.pkl") == 0) has_data = true;
        zip_file_t* file = zip_fopen_index(archive, static_cast<zip_uint64_t>(i), 0);
        if (!file) return "record '" + name + "' cannot be opened (" + zip_strerror(archive) + ")";
        zip_uint64_t total = 0;
        zip_int64_t n = 0;
        while ((n = zip_fread(file, buffer.data(), buffer.size())) > 0)
            total += static_cast<zip_uint64_t>(n);
        const std::string why = n < 0 ? zip_file_strerror(file) : "";
        zip_fclose(file);
        // libzip checks each record's CRC-32 when its last byte is read.
        if (n < 0) return "record '" + name + "' is damaged (" + why + ")";
        if (total != st.size) return "record '" + name + "' is shorter than its header says";
    }
    if (!has_data) return "not a model archive (no data.pkl record)";
    return {};
}

std::string read_checked_model_archive(const std::filesystem::path& path, const std::string& kind) {
    if (!std::filesystem::is_regular_file(path))
        throw std::runtime_error(path.string() + ": no such " + kind + " file");
    std::string bytes;
    {
        std::ifstream in(path, std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), {});
        if (!in.good() && !in.eof())
            throw std::runtime_error(path.string() + ": cannot read the " + kind + " file");
    }
    // torch trusts its archive (a damaged one can crash it): the container is checked first.
    if (const std::string problem = model_archive_problem(bytes); !problem.empty()) {
        throw std::runtime_error(path.string() + ": " + problem);
    }
    return bytes;
}

std::string first_line(const std::string& text) {
    const std::size_t start = text.find_first_not_of("\n\r ");
    if (start == std::string::npos) return "unknown error";
    const std::size_t end = text.find_first_of("\n\r", start);
    return text.substr(
        start,
        std::min<std::size_t>(end == std::string::npos ? text.size() - start : end - start, 120));
}

}  // namespace makeway::perception
