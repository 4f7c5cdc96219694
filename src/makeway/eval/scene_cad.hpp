#pragma once
// The simulator's furniture as verification libraries: what a deployment would load from the
// CAD files of its room (the paper's setting), here built from the scene's procedural models.
#include "makeway/sim/scene.hpp"
#include "makeway/verification/cad_library.hpp"

namespace makeway::eval {

/// Every furniture style generated scenes draw from (sim::scene_styles_of) at its default
/// dimensions, as a verification library: for furniture whose CAD models are not known.
verification::CadLibrary default_cad_library();
/// The CAD models of the furniture in the scene, one per distinct model (the paper's setting: the
/// robot's owner has the models of the room's chairs and tables).
verification::CadLibrary scene_cad_library(const sim::Scene& scene);

}  // namespace makeway::eval
