#pragma once
// The simulator's furniture as verification libraries: what a deployment would load from the
// CAD files of its room (the paper's setting), here built from the scene's procedural models.
#include <optional>
#include <string_view>

#include "makeway/common/name_table.hpp"
#include "makeway/sim/scene.hpp"
#include "makeway/verification/cad_library.hpp"

namespace makeway::eval {

/// Every furniture style generated scenes draw from (sim::scene_styles_of) at its default
/// dimensions, as a verification library: for furniture whose CAD models are not known.
verification::CadLibrary default_cad_library();
/// How close the library's models are to the furniture really there (issue 32: a user's CAD
/// library has similar furniture, rarely the very model).
enum class CadFit {
    kExact,            ///< the furniture's own models (the paper's setting)
    kScaled,           ///< each model scaled by 0.9-1.1 per axis (seeded by the model)
    kOtherDimensions,  ///< procedural furniture: its style at other dimensions (another model
                       ///< seed); a user's mesh: scaled as kScaled
};
/// The fits by the names the command line and the reports use ("exact", "scaled",
/// "other-dimensions"): one table for both directions.
const NameTable<CadFit>& cad_fits_by_name();
std::string_view to_string(CadFit fit);
std::optional<CadFit> parse_cad_fit(std::string_view name);

/// The CAD models of the furniture in the scene, one per distinct model (the paper's setting: the
/// robot's owner has the models of the room's chairs and tables), or approximations of them.
verification::CadLibrary scene_cad_library(const sim::Scene& scene, CadFit fit = CadFit::kExact);

}  // namespace makeway::eval
