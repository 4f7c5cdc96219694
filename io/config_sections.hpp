#pragma once
// The configuration file's layout: which stage's parameter table (common/param_table.hpp) fills
// which section, under which keys. The reader, `makeway config --describe` and the generated
// config/default.yaml all walk these sections; nothing else maps keys to members.
#include <functional>
#include <string>
#include <vector>

#include "io/config_reader.hpp"
#include "makeway/common/param_table.hpp"

namespace makeway::io {

/// One key of a section, bound to the value it sets in one configuration object.
struct BoundParam {
    std::string key;  ///< "chair.side_m": in the nested mapping `chair`
    ParamRef ref;
    ParamRange range;
    std::string doc;
    std::string old_key;  ///< the key's former name, still read (with a deprecation warning)
};

/// One top-level section of the file, bound to a configuration object.
struct BoundSection {
    std::string name;
    std::string doc;       ///< the comment on the section's line
    std::string preface;   ///< comment lines written above it (may be empty)
    std::string old_name;  ///< the section's former name, still read (with a deprecation warning)
    std::vector<BoundParam> params;
    std::function<std::vector<std::string>()> problems;  ///< each range and rule broken, by key
};

/// `table`'s keys bound to `p` (both must outlive the section).
template <class P>
BoundSection bind_section(std::string name, std::string doc, const ParamTable<P>& table, P& p,
                          std::string preface = {}) {
    BoundSection s{std::move(name), std::move(doc), std::move(preface), {}, {}, [&table, &p] {
                       return table.problems(p);
                   }};
    for (const auto& e : table.entries())
        s.params.push_back({e.key, e.ref(p), e.range, e.doc, e.old_key});
    return s;
}

/// The robot's software's sections (robot, affordance, the online system, labelling), bound to `c`.
std::vector<BoundSection> config_sections(Config& c);

/// Reads `root`'s sections into the bound objects; every problem appended (keys prefixed with
/// their section), every deprecated key read appended to `deprecated`.
void read_sections(const YAML::Node& root, std::vector<BoundSection>& sections,
                   std::vector<std::string>& problems, std::vector<std::string>& deprecated);

/// The sections as a YAML file: each key with its value and its doc as a comment.
std::string write_sections(const std::vector<BoundSection>& sections, const std::string& header);
/// One line per key: section.key, value, admitted values, unit, doc (a table for people).
std::string describe_sections(const std::vector<BoundSection>& sections);

}  // namespace makeway::io
