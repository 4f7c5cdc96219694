#pragma once
// Whitespace tokenising and strict integer parsing for the text headers of PCD and PLY.
#include <algorithm>
#include <charconv>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

namespace makeway::io {

inline bool is_space(char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v';
}

/// Splits a line on whitespace.
/// A header name (PCD field, PLY property): printable ASCII, as both formats define it. Anything
/// else is an encoding fault of the file, reported as bad input, never carried into JSON output.
inline bool is_header_name(std::string_view name) {
    return !name.empty() &&
           std::all_of(name.begin(), name.end(), [](char c) { return c > ' ' && c < 127; });
}

inline std::vector<std::string_view> split_words(std::string_view line) {
    std::vector<std::string_view> words;
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && is_space(line[i])) ++i;
        const std::size_t start = i;
        while (i < line.size() && !is_space(line[i])) ++i;
        if (i > start) words.push_back(line.substr(start, i - start));
    }
    return words;
}

/// Reads the next line (without its '\n') starting at pos, advancing pos past it.
inline std::optional<std::string_view> next_line(std::string_view text, std::size_t& pos) {
    if (pos >= text.size()) return std::nullopt;
    const std::size_t end = text.find('\n', pos);
    const std::size_t stop = end == std::string_view::npos ? text.size() : end;
    std::string_view line = text.substr(pos, stop - pos);
    pos = end == std::string_view::npos ? text.size() : end + 1;
    return line;
}

/// A whole word as a non-negative integer, or nullopt.
inline std::optional<std::uint64_t> parse_count(std::string_view word) {
    std::uint64_t value = 0;
    auto [ptr, ec] = std::from_chars(word.data(), word.data() + word.size(), value);
    if (ec != std::errc() || ptr != word.data() + word.size()) return std::nullopt;
    return value;
}

/// Pulls whitespace-separated tokens from a text body one at a time.
class TokenStream {
  public:
    explicit TokenStream(std::string_view text) : text_(text) {}
    std::optional<std::string_view> next() {
        while (pos_ < text_.size() && is_space(text_[pos_])) ++pos_;
        if (pos_ >= text_.size()) return std::nullopt;
        const std::size_t start = pos_;
        while (pos_ < text_.size() && !is_space(text_[pos_])) ++pos_;
        return text_.substr(start, pos_ - start);
    }
    bool at_end() {
        while (pos_ < text_.size() && is_space(text_[pos_])) ++pos_;
        return pos_ >= text_.size();
    }

  private:
    std::string_view text_;
    std::size_t pos_ = 0;
};

}  // namespace makeway::io
