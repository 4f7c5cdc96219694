// makeway config: the configuration as the stages' parameter tables describe it.
#include <iostream>

#include "apps/command.hpp"
#include "io/sim_config.hpp"

namespace makeway::apps {

struct ConfigOptions {
    std::string file;       ///< empty: the built-in defaults
    bool describe = false;  ///< each key's value, admitted values, unit and doc instead of YAML
};

int run_config(const ConfigOptions& options) {
    if (options.file.empty() && !options.describe) {
        std::cout << io::default_config_yaml();
        return 0;
    }
    io::SimConfig config = io::load_sim_config(options.file);  // empty: the built-in defaults
    const std::vector<io::BoundSection> sections = io::sim_config_sections(config);
    if (options.describe) {
        std::cout << io::describe_sections(sections);
    } else {
        std::cout << io::write_sections(
            sections,
            "# " + options.file + " as makeway reads it: every key, defaults filled in.\n");
    }
    return 0;
}

// The subcommands of this file, as --help lists them.
namespace {

void declare_config(CommandSpec& c, ConfigOptions& o) {
    c.option("FILE", o.file, "A configuration file to read (checked: every problem listed, exit 2)")
        .existing_file();
    c.flag("--describe", o.describe, "One line per key: value, admitted values, unit, doc");
}
const Registration<ConfigOptions> kConfig{
    "config", Group::kSetup,
    "Print the configuration: config/default.yaml as the stages' parameter "
    "tables generate it, or FILE as makeway reads it (defaults filled in)",
    declare_config, run_config};

}  // namespace

}  // namespace makeway::apps
