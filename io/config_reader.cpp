#include "io/config_reader.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>

#include "io/config_sections.hpp"
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
    T read{};
    try {
        if (!v.IsScalar()) throw YAML::Exception(YAML::Mark::null_mark(), "not a scalar");
        read = v.as<T>();
    } catch (const YAML::Exception&) {
        problems_.push_back(prefix_ + "." + key + ": must be " + type_name);
        return;
    }
    if constexpr (std::is_floating_point_v<T>) {
        if (std::isnan(read) || (!allow_infinity_ && !std::isfinite(read))) {
            problems_.push_back(
                prefix_ + "." + key +
                (allow_infinity_ ? ": must be a number or .inf" : ": must be finite"));
            return;  // one problem per key: the value's range is not judged again
        }
    }
    value = read;
}

void YamlSection::read(const char* key, double& value) { read_scalar(key, value, "a number"); }
void YamlSection::read_or_infinity(const char* key, double& value) {
    allow_infinity_ = true;
    read_scalar(key, value, "a number or .inf");
    allow_infinity_ = false;
}
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

bool YamlSection::has(const char* key) const {
    return impl_->node && impl_->node.IsMap() && impl_->node[key];
}

YAML::Node YamlSection::take(const char* key) {
    known_keys_.emplace_back(key);
    if (!impl_->node || !impl_->node.IsMap()) return YAML::Node();
    const YAML::Node& node = impl_->node;
    const YAML::Node v = node[key];
    return v ? v : YAML::Node();
}

void YamlSection::problem(const std::string& message) {
    problems_.push_back(prefix_ + ": " + message);
}

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

YAML::Node load_yaml(std::string_view text) {
    try {
        return YAML::Load(std::string(text));
    } catch (const YAML::Exception& e) {
        throw FormatError("YAML syntax error at line " + std::to_string(e.mark.line + 1) + ": " +
                          e.msg);
    }
}

namespace {

YAML::Node parse_yaml_root(std::string_view yaml_text) {
    const YAML::Node root = load_yaml(yaml_text);
    if (root && !root.IsNull() && !root.IsMap()) {
        throw FormatError("the top level must be a mapping of section names");
    }
    return root;
}

void report_unknown_sections(const YAML::Node& root, const std::vector<BoundSection>& known,
                             std::vector<std::string>& problems) {
    if (!root.IsMap()) return;
    for (const auto& kv : root) {
        const std::string name = kv.first.as<std::string>("");
        const bool simulator = std::find(kSimulatorSections.begin(), kSimulatorSections.end(),
                                         name) != kSimulatorSections.end();
        const bool ours = std::any_of(known.begin(), known.end(),
                                      [&](const BoundSection& s) { return s.name == name; });
        if (!simulator && !ours) problems.push_back(name + ": unknown section");
    }
}

}  // namespace

namespace detail {

void parse_into(std::string_view yaml_text, Config& config, const MoreSections& more,
                std::vector<std::string>* deprecated) {
    const YAML::Node root = parse_yaml_root(yaml_text);
    std::vector<std::string> problems, old_keys;
    std::vector<BoundSection> sections = config_sections(config);
    report_unknown_sections(root, sections, problems);
    read_sections(root, sections, problems, old_keys);
    config.system.navigator.affordance = config.affordance;
    if (more) more(root, problems, old_keys);
    if (!problems.empty()) throw FormatError(join_problems(problems));
    if (deprecated)
        *deprecated = old_keys;
    else
        for (const std::string& d : old_keys) print_warning(d);
}

void load_into(const std::filesystem::path& path, Config& config, const MoreSections& more) {
    const std::string text = read_file(path, /*allow_empty=*/true);
    std::vector<std::string> deprecated;
    try {
        parse_into(text, config, more, &deprecated);
    } catch (const FormatError& e) {
        throw FileError(path.string(), e.what());
    }
    for (const std::string& d : deprecated)
        print_warning(path.string() + ": " + d + " (the old name is read until the next release)");
}

}  // namespace detail

Config parse_config(std::string_view yaml_text) {
    Config config;
    detail::parse_into(yaml_text, config, {});
    return config;
}

Config load_config(const std::filesystem::path& path) {
    Config config;
    if (!path.empty()) detail::load_into(path, config, {});
    return config;
}

pipeline::SystemParams online_system_params(const Config& config, const Isometry3* T_base_sensor) {
    pipeline::SystemParams p = config.system;
    p.navigator.affordance = config.affordance;
    p.navigator.affordance_layer = true;
    pipeline::apply_robot(config.robot, p, T_base_sensor);
    return p;
}

}  // namespace makeway::io
