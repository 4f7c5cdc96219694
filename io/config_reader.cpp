#include "io/config_reader.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>

#include "io/error.hpp"
#include "io/file_util.hpp"

namespace makeway::io {
namespace {

// Edit distance, for "did you mean" suggestions on misspelt keys.
std::size_t edit_distance(std::string_view a, std::string_view b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diag = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t up = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] != b[j - 1])});
            diag = up;
        }
    }
    return row[b.size()];
}

}  // namespace

struct YamlSection::Impl {
    YAML::Node node;
};

YamlSection::YamlSection(const YAML::Node& node, std::string prefix,
                         std::vector<std::string>& problems)
    : impl_(new Impl{node}), prefix_(std::move(prefix)), problems_(problems) {
    if (node && !node.IsNull() && !node.IsMap()) {
        problems_.push_back(prefix_ + ": must be a mapping of keys to values");
        impl_->node = YAML::Node();
    }
}

YamlSection::~YamlSection() { delete impl_; }

template <typename T>
void YamlSection::read_scalar(const char* key, T& value, const char* type_name) {
    known_keys_.emplace_back(key);
    if (!impl_->node || !impl_->node.IsMap()) return;
    const YAML::Node& node = impl_->node;
    const YAML::Node v = node[key];
    if (!v) return;
    try {
        if (!v.IsScalar()) throw YAML::Exception(YAML::Mark::null_mark(), "not a scalar");
        value = v.as<T>();
    } catch (const YAML::Exception&) {
        problems_.push_back(prefix_ + "." + key + ": must be " + type_name);
        return;
    }
    if constexpr (std::is_floating_point_v<T>) {
        if (!std::isfinite(value)) problems_.push_back(prefix_ + "." + key + ": must be finite");
    }
}

void YamlSection::read(const char* key, double& value) { read_scalar(key, value, "a number"); }
void YamlSection::read(const char* key, int& value) { read_scalar(key, value, "an integer"); }
void YamlSection::read(const char* key, std::uint64_t& value) {
    read_scalar(key, value, "a non-negative integer");
}
void YamlSection::read(const char* key, bool& value) { read_scalar(key, value, "true or false"); }
void YamlSection::read(const char* key, std::string& value) { read_scalar(key, value, "a string"); }

void YamlSection::read(const char* key, std::uint32_t& value) {
    read_scalar(key, value, "a non-negative integer");
}

void YamlSection::read(const char* key, Eigen::Vector2d& value) {
    known_keys_.emplace_back(key);
    if (!impl_->node || !impl_->node.IsMap()) return;
    const YAML::Node& node = impl_->node;
    const YAML::Node v = node[key];
    if (!v) return;
    try {
        if (!v.IsSequence() || v.size() != 2) throw YAML::Exception(YAML::Mark::null_mark(), "");
        value = Eigen::Vector2d(v[0].as<double>(), v[1].as<double>());
    } catch (const YAML::Exception&) {
        problems_.push_back(prefix_ + "." + key + ": must be a pair of numbers [a, b]");
        return;
    }
    if (!value.allFinite()) problems_.push_back(prefix_ + "." + key + ": must be finite");
}

YAML::Node YamlSection::take(const char* key) {
    known_keys_.emplace_back(key);
    if (!impl_->node || !impl_->node.IsMap()) return YAML::Node();
    const YAML::Node& node = impl_->node;
    const YAML::Node v = node[key];
    return v ? v : YAML::Node();
}

void YamlSection::problem(const std::string& message) { problems_.push_back(prefix_ + ": " + message); }

void YamlSection::add_validation(const std::vector<std::string>& messages) {
    for (const auto& m : messages) problems_.push_back(prefix_ + "." + m);
}

void YamlSection::finish() {
    if (!impl_->node || !impl_->node.IsMap()) return;
    for (const auto& kv : impl_->node) {
        const std::string key = kv.first.as<std::string>("");
        if (std::find(known_keys_.begin(), known_keys_.end(), key) != known_keys_.end()) continue;
        std::string msg = prefix_ + "." + key + ": unknown key";
        const auto best = std::min_element(known_keys_.begin(), known_keys_.end(),
                                           [&](const auto& a, const auto& b) {
                                               return edit_distance(key, a) < edit_distance(key, b);
                                           });
        if (best != known_keys_.end() && edit_distance(key, *best) <= 2) {
            msg += " (did you mean '" + *best + "'?)";
        }
        problems_.push_back(msg);
    }
}

Config parse_config(std::string_view yaml_text) {
    YAML::Node root;
    try {
        root = YAML::Load(std::string(yaml_text));
    } catch (const YAML::Exception& e) {
        throw FormatError("YAML syntax error at line " + std::to_string(e.mark.line + 1) + ": " +
                          e.msg);
    }
    std::vector<std::string> problems;
    if (root && !root.IsNull() && !root.IsMap()) {
        throw FormatError("the top level must be a mapping of section names");
    }
    Config cfg;
    const std::vector<std::string> sections{"layout", "sampling"};
    if (root.IsMap()) {
        for (const auto& kv : root) {
            const std::string name = kv.first.as<std::string>("");
            if (std::find(sections.begin(), sections.end(), name) == sections.end()) {
                problems.push_back(name + ": unknown section");
            }
        }
    }
    {
        YamlSection s(root["layout"], "layout", problems);
        s.read("seed", cfg.layout.seed);
        s.read("num_objects", cfg.layout.num_objects);
        s.read("room_size_m", cfg.layout.room_size_m);
        s.read("table_share", cfg.layout.table_share);
        s.finish();
        s.add_validation(cfg.layout.validate());
    }
    {
        YamlSection s(root["sampling"], "sampling", problems);
        s.read("points_per_m2", cfg.sampling.points_per_m2);
        s.read("noise_m", cfg.sampling.noise_m);
        s.read("skip_bottom", cfg.sampling.skip_bottom);
        s.finish();
        s.add_validation(validate(cfg.sampling));
    }
    if (!problems.empty()) {
        std::string msg = problems.size() == 1 ? std::string() :
                          std::to_string(problems.size()) + " problems: ";
        for (std::size_t i = 0; i < problems.size(); ++i) msg += (i ? "; " : "") + problems[i];
        throw FormatError(msg);
    }
    return cfg;
}

Config load_config(const std::filesystem::path& path) {
    const std::string text = read_file(path, /*allow_empty=*/true);
    try {
        return parse_config(text);
    } catch (const FormatError& e) {
        throw FileError(path.string(), e.what());
    }
}

}  // namespace makeway::io
