#pragma once
// Parametric CAD models of chairs and tables. Dimensions are drawn from real furniture ranges with
// a seed, so a (style, seed) pair names one model exactly.
//
// Object frame: origin at the centre of the footprint on the floor, z up, +x forward. For a chair,
// forward is the way a seated person faces (pulling a chair out moves it along -x); for a table,
// x runs along its length and people sit on the +-y sides.
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "makeway/common/oriented_box.hpp"
#include "makeway/common/semantic_label.hpp"
#include "makeway/common/triangle_mesh.hpp"

namespace makeway::sim {

enum class FurnitureStyle : std::uint8_t {
    kFourLegChair,
    kOfficeChair,
    kStool,
    kArmchair,
    kRectTable,
    kRoundTable,
    kConferenceTable,
    // The wider world (issue "auto-labelling"): styles generated scenes do not draw by default.
    kStackingChair,
    kSledChair,        ///< on two floor runners (a low part the robot can hit)
    kCantileverChair,  ///< a tube frame that rests on the floor front and back
    kBarStool,
    kFoldingChair,
    kBench,
    kSofa,
    kLoungeChair,
    kPedestalTable,  ///< a cafe table: one column on a cross foot
    kCoffeeTable,
    kBalconyTable,  ///< small, round, three thin legs
    kDesk,
    kFoldingTable,
    kSideTable,
};
constexpr int kNumFurnitureStyles = 21;

std::string_view to_string(FurnitureStyle style);
std::optional<FurnitureStyle> parse_furniture_style(std::string_view name);
ObjectClass class_of(FurnitureStyle style);
/// Every style of the class.
std::vector<FurnitureStyle> styles_of(ObjectClass cls);
/// The seven styles generated scenes draw from (and the benchmarks measured on them): four chairs,
/// three tables.
std::vector<FurnitureStyle> scene_styles_of(ObjectClass cls);

struct FurnitureModel {
    FurnitureStyle style = FurnitureStyle::kFourLegChair;
    std::uint64_t seed = 0;
    TriangleMesh mesh_object;  ///< in the object frame
    OrientedBox box_object;    ///< tight box in the object frame (yaw 0, centre at (0, 0, h/2))
};

/// The model of `style` with dimensions drawn from `seed`.
FurnitureModel make_furniture(FurnitureStyle style, std::uint64_t seed);

}  // namespace makeway::sim
