#include "io/dataset_io.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "io/error.hpp"
#include "io/file_util.hpp"
#include "io/json_io.hpp"
#include "io/point_cloud_io.hpp"
#include "io/tracking_io.hpp"

namespace makeway::io {
namespace {

Json labelled_objects_to_json(const std::vector<LabelledObject>& objects) {
    Json out = Json::array();
    for (const LabelledObject& o : objects) {
        out.push_back({{"id", o.id},
                       {"class", std::string(to_string(o.cls))},
                       {"style", o.style},
                       {"box", to_json(o.box_sensor)},
                       {"points", o.points}});
    }
    return out;
}

LabelledObject object_from_json(const Json& o) {
    LabelledObject lo;
    if (!o.is_object() || !o.contains("class") || !o["class"].is_string() ||
        !parse_object_class(o["class"].get<std::string>())) {
        throw FormatError("'class' must be chair or table");
    }
    lo.cls = *parse_object_class(o["class"].get<std::string>());
    if (!o.contains("box")) throw FormatError("missing 'box'");
    lo.box_sensor = box_from_json(o["box"]);
    if (o.contains("style") && o["style"].is_string()) lo.style = o["style"].get<std::string>();
    if (o.contains("points") && o["points"].is_number_unsigned())
        lo.points = o["points"].get<std::size_t>();
    if (o.contains("id")) {
        if (!o["id"].is_number_unsigned() || o["id"].get<std::uint64_t>() > 0xffffffffULL)
            throw FormatError("'id' must be an unsigned 32-bit integer");
        lo.id = o["id"].get<std::uint32_t>();
    }
    return lo;
}

// Keyframe fields beyond the objects are optional: datasets written before they existed, and
// hand-labelled data without poses, still load (as one sequence with identity poses).
void read_keyframe_fields(const Json& j, LabelledKeyframe& kf) {
    if (j.contains("sequence")) {
        if (!j["sequence"].is_number_unsigned() ||
            j["sequence"].get<std::uint64_t>() > 0xffffffffULL)
            throw FormatError("'sequence' must be an unsigned integer");
        kf.sequence = j["sequence"].get<std::uint32_t>();
    }
    if (j.contains("stamp_s")) {
        if (!j["stamp_s"].is_number() || !std::isfinite(j["stamp_s"].get<double>()))
            throw FormatError("'stamp_s' must be a finite number");
        kf.stamp_s = j["stamp_s"].get<double>();
    }
    if (j.contains("T_world_sensor"))
        kf.T_world_sensor = pose_from_json(j["T_world_sensor"], "T_world_sensor");
    if (j.contains("ground_plane")) {
        const Json& g = j["ground_plane"];
        if (!g.is_array() || g.size() != 4 || !std::all_of(g.begin(), g.end(), [](const Json& v) {
                return v.is_number() && std::isfinite(v.get<double>());
            }))
            throw FormatError("'ground_plane' must be 4 finite numbers (normal, offset)");
        kf.ground_plane_sensor = Eigen::Vector4d(g[0].get<double>(), g[1].get<double>(),
                                                 g[2].get<double>(), g[3].get<double>());
        if (std::abs(kf.ground_plane_sensor->head<3>().norm() - 1.0) > 0.01)
            throw FormatError("'ground_plane' normal must be a unit vector");
    }
}

}  // namespace

void write_labelled_keyframe(const std::filesystem::path& dir, std::size_t index,
                             const LabelledKeyframe& kf) {
    const std::string name = frame_name(index);
    PointCloud xyzi;
    xyzi.xyz = kf.cloud_sensor.xyz;
    xyzi.intensity = kf.cloud_sensor.intensity.size() == kf.cloud_sensor.size()
                         ? kf.cloud_sensor.intensity
                         : std::vector<float>(kf.cloud_sensor.size(), 0.0f);
    write_point_cloud(dir / "clouds" / (name + ".bin"), xyzi);
    Json label{{"objects", labelled_objects_to_json(kf.objects)},
               {"unseen", labelled_objects_to_json(kf.unseen)},
               {"sequence", kf.sequence},
               {"stamp_s", kf.stamp_s},
               {"T_world_sensor", pose_to_json(kf.T_world_sensor)}};
    if (kf.ground_plane_sensor) {
        const Eigen::Vector4d& g = *kf.ground_plane_sensor;
        label["ground_plane"] = {g(0), g(1), g(2), g(3)};
    }
    write_json(dir / "labels" / (name + ".json"), label);
}

std::vector<LabelledKeyframe> read_detection_dataset(
    const std::filesystem::path& dir,
    const std::function<void(std::size_t, std::size_t)>& progress) {
    const auto labels = frame_files(dir / "labels", "json");
    std::vector<LabelledKeyframe> out;
    for (const auto& label_file : labels) {
        LabelledKeyframe kf;
        const auto cloud_file = dir / "clouds" / (label_file.stem().string() + ".bin");
        kf.cloud_sensor = read_point_cloud(cloud_file).cloud;
        const Json j = read_json(label_file);
        if (!j.is_object() || !j.contains("objects") || !j["objects"].is_array())
            throw FileError(label_file.string(), "expected {\"objects\": [...]}");
        for (const char* list : {"objects", "unseen"}) {
            if (!j.contains(list)) continue;
            if (!j[list].is_array())
                throw FileError(label_file.string(), std::string("'") + list + "' must be a list");
            for (std::size_t i = 0; i < j[list].size(); ++i) {
                try {
                    (std::string(list) == "objects" ? kf.objects : kf.unseen)
                        .push_back(object_from_json(j[list][i]));
                } catch (const FormatError& e) {
                    throw FileError(label_file.string(),
                                    std::string(list) + " " + std::to_string(i) + ": " + e.what());
                }
            }
        }
        try {
            read_keyframe_fields(j, kf);
        } catch (const FormatError& e) {
            throw FileError(label_file.string(), e.what());
        }
        out.push_back(std::move(kf));
        if (progress) progress(out.size(), labels.size());
    }
    return out;
}

}  // namespace makeway::io
