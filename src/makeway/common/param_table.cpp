#include "makeway/common/param_table.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <stdexcept>

namespace makeway {

bool ParamRange::contains(double v) const {
    if (std::isnan(v)) return false;
    if (std::isinf(v)) return infinity && v > 0.0;
    return (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
}

std::string ParamRange::text() const {
    // A 64-bit seed's range ends at 2^64 (the double just above its largest value).
    const bool any_seed = hi >= 18446744073709551615.0;
    return std::string(lo_open ? "(" : "[") + param_number(lo) + ", " +
           (any_seed ? "2^64)" : param_number(hi) + (hi_open ? ")" : "]")) +
           (infinity ? " or .inf" : "");
}

std::string join_problems(const std::vector<std::string>& problems) {
    std::string msg =
        problems.size() == 1 ? std::string() : std::to_string(problems.size()) + " problems: ";
    for (std::size_t i = 0; i < problems.size(); ++i) msg += (i ? "; " : "") + problems[i];
    return msg;
}

std::string join_alternatives(const std::vector<std::string>& names) {
    std::string list;
    for (std::size_t k = 0; k < names.size(); ++k)
        list += (k == 0 ? "" : k + 1 == names.size() ? " or " : ", ") + names[k];
    return list;
}

void throw_if_problems(const std::vector<std::string>& problems, const std::string& what) {
    if (!problems.empty())
        throw std::invalid_argument((what.empty() ? std::string() : what + ": ") +
                                    join_problems(problems));
}

std::string param_unit(const std::string& key) {
    // Longest suffix first: _radps2 before _radps before _rad.
    static const std::array<std::pair<const char*, const char*>, 11> kUnits{
        {{"_radps2", "rad/s^2"},
         {"_mps2", "m/s^2"},
         {"_radps", "rad/s"},
         {"_mps", "m/s"},
         {"_per_m", "per m"},
         {"_per_rad", "per rad"},
         {"_deg", "deg"},
         {"_rad", "rad"},
         {"_hz", "Hz"},
         {"_m", "m"},
         {"_s", "s"}}};
    for (const auto& [suffix, unit] : kUnits) {
        const std::string s(suffix);
        if (key.size() > s.size() && key.compare(key.size() - s.size(), s.size(), s) == 0)
            return unit;
    }
    return "";
}

std::string param_number(double v) {
    if (std::isnan(v)) return ".nan";
    if (std::isinf(v)) return v > 0 ? ".inf" : "-.inf";
    // Whole numbers below 2^53 as integers, others the shortest text that reads back to v.
    if (v == std::floor(v) && std::abs(v) < 9.007199254740992e15)
        return std::to_string(static_cast<long long>(v));
    std::array<char, 64> buf{};
    const auto [end, ec] =
        std::to_chars(buf.data(), buf.data() + buf.size(), v, std::chars_format::general);
    return ec == std::errc() ? std::string(buf.data(), end) : std::to_string(v);
}

}  // namespace makeway
