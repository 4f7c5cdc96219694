#include <algorithm>

#include "makeway/labelling/param_tables.hpp"

namespace makeway::labelling {

LabelParams::LabelParams() {
    // Clusters are rough boxes: every model of the class is tried, whatever its size.
    verify.max_size_mismatch = 1.2;
    verify.max_models = 32;
    verify.box_margin_m = 0.05;
    verify.num_threads = 1;
    // A session's map is many keyframes of a still object: its fit is tighter than one keyframe's.
    verify.e_max_m = 0.025;
}

std::vector<std::string> LabelParams::validate() const {
    std::vector<std::string> e = system.validate();
    for (const std::string& s : align.validate()) e.push_back(s);
    const std::vector<std::string> table = label_table().problems(*this);
    for (const std::string& s : table) e.push_back("labelling." + s);
    // The verifier's own checks cover the members no file sets; a bad e_max_m (the one a file
    // does set, as verify_e_max_m) the table has just reported under its key, once is enough.
    const bool e_max_reported = std::any_of(table.begin(), table.end(), [](const std::string& s) {
        return s.find("verify_e_max_m") != std::string::npos;
    });
    if (!e_max_reported) {
        for (const std::string& s : verify.validate()) e.push_back("labelling.verify: " + s);
    }
    if (!(occupancy.max_range_m > 0.0)) e.push_back("labelling.max_range_m must be > 0");
    if (!(unknown_box_margin_m >= 0.0 && unknown_box_margin_m <= 10.0))
        e.push_back("labelling.unknown_box_margin_m must be in [0, 10]");
    return e;
}

}  // namespace makeway::labelling
