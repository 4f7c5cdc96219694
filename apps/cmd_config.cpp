// makeway config: the configuration as the stages' parameter tables describe it.
#include <iostream>

#include "apps/commands.hpp"
#include "io/sim_config.hpp"

namespace makeway::apps {

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

}  // namespace makeway::apps
