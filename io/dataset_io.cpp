#include "io/dataset_io.hpp"

#include <cstdio>

#include "io/error.hpp"
#include "io/json_io.hpp"
#include "io/point_cloud_io.hpp"
#include "io/tracking_io.hpp"

namespace makeway::io {
namespace {

std::string frame_name(std::size_t index) {
    char buf[16];
    std::snprintf(buf, sizeof(buf), "%06zu", index);
    return buf;
}

}  // namespace

void write_labelled_keyframe(const std::filesystem::path& dir, std::size_t index, const LabelledKeyframe& kf) {
    const std::string name = frame_name(index);
    PointCloud xyzi;
    xyzi.xyz = kf.cloud_sensor.xyz;
    xyzi.intensity = kf.cloud_sensor.intensity.size() == kf.cloud_sensor.size() ? kf.cloud_sensor.intensity
                                                                                   : std::vector<float>(kf.cloud_sensor.size(), 0.0f);
    write_point_cloud(dir / "clouds" / (name + ".bin"), xyzi);
    Json objects = Json::array();
    for (const LabelledObject& o : kf.objects) {
        objects.push_back({{"class", std::string(to_string(o.cls))}, {"style", o.style}, {"box", to_json(o.box_sensor)}, {"points", o.points}});
    }
    write_json(dir / "labels" / (name + ".json"), {{"objects", objects}});
}

std::vector<LabelledKeyframe> read_detection_dataset(const std::filesystem::path& dir,
                                                     const std::function<void(std::size_t, std::size_t)>& progress) {
    const auto labels = frame_files(dir / "labels", "json");
    std::vector<LabelledKeyframe> out;
    for (const auto& label_file : labels) {
        LabelledKeyframe kf;
        const auto cloud_file = dir / "clouds" / (label_file.stem().string() + ".bin");
        kf.cloud_sensor = read_point_cloud(cloud_file).cloud;
        const Json j = read_json(label_file);
        if (!j.is_object() || !j.contains("objects") || !j["objects"].is_array()) throw FileError(label_file.string(), "expected {\"objects\": [...]}");
        for (std::size_t i = 0; i < j["objects"].size(); ++i) {
            const Json& o = j["objects"][i];
            try {
                LabelledObject lo;
                if (!o.is_object() || !o.contains("class") || !o["class"].is_string() || !parse_object_class(o["class"].get<std::string>())) {
                    throw FormatError("'class' must be chair or table");
                }
                lo.cls = *parse_object_class(o["class"].get<std::string>());
                if (!o.contains("box")) throw FormatError("missing 'box'");
                lo.box_sensor = box_from_json(o["box"]);
                if (o.contains("style") && o["style"].is_string()) lo.style = o["style"].get<std::string>();
                if (o.contains("points") && o["points"].is_number_unsigned()) lo.points = o["points"].get<std::size_t>();
                kf.objects.push_back(lo);
            } catch (const FormatError& e) {
                throw FileError(label_file.string(), "object " + std::to_string(i) + ": " + e.what());
            }
        }
        out.push_back(std::move(kf));
        if (progress) progress(out.size(), labels.size());
    }
    return out;
}

}  // namespace makeway::io
