#include "makeway/common/semantic_label.hpp"

namespace makeway {
namespace {
constexpr std::array<std::string_view, kNumSemanticLabels> kLabelNames{
    "unlabelled", "ground", "ceiling", "structure", "chair", "table", "person", "clutter"};
}  // namespace

std::string_view to_string(SemanticLabel label) {
    const auto i = static_cast<std::size_t>(label);
    return i < kLabelNames.size() ? kLabelNames[i] : std::string_view("invalid");
}

std::string_view to_string(ObjectClass cls) {
    return cls == ObjectClass::kChair ? "chair" : "table";
}

std::optional<SemanticLabel> parse_semantic_label(std::string_view name) {
    for (std::size_t i = 0; i < kLabelNames.size(); ++i) {
        if (kLabelNames[i] == name) return static_cast<SemanticLabel>(i);
    }
    return std::nullopt;
}

std::optional<ObjectClass> parse_object_class(std::string_view name) {
    for (ObjectClass cls : kAllObjectClasses) {
        if (to_string(cls) == name) return cls;
    }
    return std::nullopt;
}

SemanticLabel to_semantic_label(ObjectClass cls) {
    return cls == ObjectClass::kChair ? SemanticLabel::kChair : SemanticLabel::kTable;
}

std::optional<ObjectClass> to_object_class(SemanticLabel label) {
    if (label == SemanticLabel::kChair) return ObjectClass::kChair;
    if (label == SemanticLabel::kTable) return ObjectClass::kTable;
    return std::nullopt;
}

}  // namespace makeway
