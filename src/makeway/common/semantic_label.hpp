#pragma once
// Per-point semantic labels and the object classes the detector, tracker and costmap know.
#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

namespace makeway {

/// Stored in a point cloud's `label` field (uint8). Values are part of the file formats: append
/// only.
enum class SemanticLabel : std::uint8_t {
    kUnlabelled = 0,
    kGround = 1,
    kCeiling = 2,
    kStructure = 3,  ///< walls, doors, pillars: never move
    kChair = 4,
    kTable = 5,
    kPerson = 6,
    kClutter = 7,  ///< other objects (background class for the detector)
};
constexpr int kNumSemanticLabels = 8;

/// Classes with an affordance costmap. Index into class-probability vectors.
enum class ObjectClass : std::uint8_t { kChair = 0, kTable = 1 };
constexpr int kNumObjectClasses = 2;
constexpr std::array<ObjectClass, kNumObjectClasses> kAllObjectClasses{ObjectClass::kChair,
                                                                       ObjectClass::kTable};

std::string_view to_string(SemanticLabel label);
std::string_view to_string(ObjectClass cls);
std::optional<SemanticLabel> parse_semantic_label(std::string_view name);
std::optional<ObjectClass> parse_object_class(std::string_view name);

SemanticLabel to_semantic_label(ObjectClass cls);
/// The object class of a point label, if it has one (chair, table).
std::optional<ObjectClass> to_object_class(SemanticLabel label);

}  // namespace makeway
