#include "io/tracking_io.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>

#include "io/error.hpp"
#include "io/file_util.hpp"
#include "io/text_scan.hpp"
#include "makeway/common/angles.hpp"

namespace makeway::io {
namespace {

double number(std::string_view w, const std::string& where) {
    double v = 0.0;
    auto [ptr, ec] = std::from_chars(w.data(), w.data() + w.size(), v);
    if (ec != std::errc() || ptr != w.data() + w.size())
        throw FormatError(where + "bad number '" + std::string(w.substr(0, 40)) + "'");
    if (!std::isfinite(v)) throw FormatError(where + "value is NaN or infinite");
    return v;
}

int integer(std::string_view w, const std::string& where) {
    int v = 0;
    auto [ptr, ec] = std::from_chars(w.data(), w.data() + w.size(), v);
    if (ec != std::errc() || ptr != w.data() + w.size())
        throw FormatError(where + "bad integer '" + std::string(w.substr(0, 40)) + "'");
    return v;
}

void append(std::string& out, double v) {
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof(buf), v);
    out.append(buf, r.ptr);
}

// AB3DMOT's detection files (its data/KITTI/detection/): comma-separated
//   frame, type (1 Pedestrian, 2 Car, 3 Cyclist), x1, y1, x2, y2, score, h, w, l, x, y, z,
//   rotation_y, alpha
// with the score a raw logit. Read into the same records as KITTI's own text.
KittiTrackingRecord parse_ab3dmot_line(std::string_view line, const std::string& where) {
    std::vector<std::string_view> f;
    for (std::size_t start = 0;;) {
        const std::size_t comma = line.find(',', start);
        std::string_view w = line.substr(
            start, comma == std::string_view::npos ? std::string_view::npos : comma - start);
        while (!w.empty() && std::isspace(static_cast<unsigned char>(w.front())))
            w.remove_prefix(1);
        while (!w.empty() && std::isspace(static_cast<unsigned char>(w.back()))) w.remove_suffix(1);
        f.push_back(w);
        if (comma == std::string_view::npos) break;
        start = comma + 1;
    }
    if (f.size() != 15)
        throw FormatError(where +
                          "expected 15 comma-separated fields (AB3DMOT detections), found " +
                          std::to_string(f.size()));
    KittiTrackingRecord r;
    r.frame = integer(f[0], where);
    if (r.frame < 0) throw FormatError(where + "negative frame");
    const int type = integer(f[1], where);
    static constexpr const char* kTypes[] = {"Pedestrian", "Car", "Cyclist"};
    if (type < 1 || type > 3)
        throw FormatError(where + "type " + std::to_string(type) +
                          " is not 1 (Pedestrian), 2 (Car) or 3 (Cyclist)");
    r.type = kTypes[type - 1];
    std::array<double, 13> v{};
    for (std::size_t i = 0; i < 13; ++i) v[i] = number(f[2 + i], where);
    r.bbox_px = {v[0], v[1], v[2], v[3]};
    r.score = v[4];
    r.h_m = v[5], r.w_m = v[6], r.l_m = v[7];
    r.location_cam_m = {v[8], v[9], v[10]};
    r.rotation_y_rad = v[11];
    r.alpha = v[12];
    if (!(r.h_m > 0 && r.w_m > 0 && r.l_m > 0))
        throw FormatError(where + "box dimensions must be > 0");
    return r;
}

}  // namespace

std::vector<KittiTrackingRecord> parse_kitti_tracking(std::string_view text) {
    std::vector<KittiTrackingRecord> out;
    std::size_t pos = 0, line_no = 0;
    while (const auto line = next_line(text, pos)) {
        ++line_no;
        const auto w = split_words(*line);
        if (w.empty() || w[0].front() == '#') continue;
        const std::string where = "line " + std::to_string(line_no) + ": ";
        if (line->find(',') != std::string_view::npos) {
            out.push_back(parse_ab3dmot_line(*line, where));
            continue;
        }
        // frame [id] type + 14 numbers [+ score]; a track id is there when the second word is a
        // number.
        const bool has_id =
            w.size() >= 2 &&
            (std::isdigit(static_cast<unsigned char>(w[1].front())) || w[1].front() == '-');
        const std::size_t base = has_id ? 2 : 1;  // index of the type
        if (w.size() != base + 15 && w.size() != base + 16) {
            throw FormatError(where + "expected " + std::to_string(base + 15) + " or " +
                              std::to_string(base + 16) + " fields, found " +
                              std::to_string(w.size()));
        }
        KittiTrackingRecord r;
        r.frame = integer(w[0], where);
        if (r.frame < 0) throw FormatError(where + "negative frame");
        if (has_id) r.track_id = integer(w[1], where);
        r.type = std::string(w[base]);
        std::array<double, 14> v{};
        for (std::size_t i = 0; i < 14; ++i) v[i] = number(w[base + 1 + i], where);
        r.truncated = v[0], r.occluded = v[1], r.alpha = v[2];
        r.bbox_px = {v[3], v[4], v[5], v[6]};
        r.h_m = v[7], r.w_m = v[8], r.l_m = v[9];
        r.location_cam_m = {v[10], v[11], v[12]};
        r.rotation_y_rad = v[13];
        if (w.size() == base + 16) r.score = number(w[base + 15], where);
        // DontCare regions have a 2D box only (size -1, location -1000): they are kept as such.
        if (!r.is_dont_care() && !(r.h_m > 0 && r.w_m > 0 && r.l_m > 0))
            throw FormatError(where + "box dimensions must be > 0");
        out.push_back(r);
    }
    return out;
}

bool KittiTrackingRecord::is_dont_care() const { return to_lower(type) == "dontcare"; }

std::vector<KittiTrackingRecord> read_kitti_tracking(const std::filesystem::path& path) {
    const std::string text =
        read_file(path, /*allow_empty=*/true);  // a sequence without objects is valid
    try {
        return parse_kitti_tracking(text);
    } catch (const FormatError& e) {
        throw FileError(path.string(), e.what());
    }
}

void write_kitti_tracking(const std::filesystem::path& path,
                          const std::vector<KittiTrackingRecord>& records) {
    std::string out;
    for (const auto& r : records) {
        out += std::to_string(r.frame) + " ";
        if (r.track_id >= 0) out += std::to_string(r.track_id) + " ";
        out += r.type;
        for (double v : {r.truncated, r.occluded, r.alpha, r.bbox_px[0], r.bbox_px[1], r.bbox_px[2],
                         r.bbox_px[3], r.h_m, r.w_m, r.l_m, r.location_cam_m.x(),
                         r.location_cam_m.y(), r.location_cam_m.z(), r.rotation_y_rad}) {
            out += ' ';
            append(out, v);
        }
        if (r.score) {
            out += ' ';
            append(out, *r.score);
        }
        out += '\n';
    }
    write_file_atomic(path, out);
}

std::optional<ObjectClass> class_of_kitti_type(std::string_view type) {
    return parse_object_class(to_lower(std::string(type)));
}

KittiTrackingRecord to_kitti(const OrientedBox& b, ObjectClass cls, int frame, int track_id,
                             std::optional<double> score) {
    return to_kitti(b, cls == ObjectClass::kChair ? "Chair" : "Table", frame, track_id, score);
}

KittiTrackingRecord to_kitti(const OrientedBox& b, const std::string& type, int frame, int track_id,
                             std::optional<double> score) {
    KittiTrackingRecord r;
    r.frame = frame;
    r.track_id = track_id;
    r.type = type;
    r.l_m = b.size_m.x(), r.w_m = b.size_m.y(), r.h_m = b.size_m.z();
    r.location_cam_m = {-b.centre_m.y(), -(b.centre_m.z() - 0.5 * b.size_m.z()), b.centre_m.x()};
    r.rotation_y_rad = wrap_angle(-b.yaw_rad - kPi / 2);
    r.alpha = wrap_angle(r.rotation_y_rad - std::atan2(r.location_cam_m.x(), r.location_cam_m.z()));
    r.bbox_px = {-1, -1, -1, -1};  // no camera
    r.score = score;
    return r;
}

OrientedBox box_from_kitti(const KittiTrackingRecord& r) {
    OrientedBox b;
    b.size_m = {r.l_m, r.w_m, r.h_m};
    b.centre_m = {r.location_cam_m.z(), -r.location_cam_m.x(), -r.location_cam_m.y() + 0.5 * r.h_m};
    b.yaw_rad = wrap_angle(-r.rotation_y_rad - kPi / 2);
    return b;
}

namespace {

Detection detection_from_json(const Json& d, bool any_score) {
    Detection det;
    if (!d.is_object() || !d.contains("class") || !d["class"].is_string())
        throw FormatError("'class' must be chair or table");
    const auto cls = parse_object_class(d["class"].get<std::string>());
    if (!cls) throw FormatError("'class' must be chair or table");
    det.cls = *cls;
    det.box_sensor = box_from_json(d.contains("box") ? d["box"] : d);
    det.score = 1.0;
    if (d.contains("score")) {
        if (!d["score"].is_number() || !std::isfinite(d["score"].get<double>()))
            throw FormatError("'score' must be a number");
        if (!any_score && !(d["score"].get<double>() >= 0.0 && d["score"].get<double>() <= 1.0)) {
            throw FormatError("'score' must be a number in [0, 1]");
        }
        det.score = d["score"].get<double>();
    }
    det.class_probabilities.fill(0.0);
    det.class_probabilities[static_cast<std::size_t>(det.cls)] = 1.0;
    if (d.contains("class_probabilities")) {
        const Json& p = d["class_probabilities"];
        if (!p.is_array() || p.size() != kNumObjectClasses)
            throw FormatError("'class_probabilities' must list chair and table");
        for (std::size_t c = 0; c < kNumObjectClasses; ++c) {
            if (!p[c].is_number() || !(p[c].get<double>() >= 0.0 && p[c].get<double>() <= 1.0)) {
                throw FormatError("'class_probabilities' must be numbers in [0, 1]");
            }
            det.class_probabilities[c] = p[c].get<double>();
        }
    }
    return det;
}

}  // namespace

DetectionFrame parse_detection_frame(std::string_view text, bool any_score) {
    Json j;
    try {
        j = Json::parse(text);
    } catch (
        const Json::exception& e) {  // parse_error, and out_of_range for a number that overflows
        throw FormatError(std::string("invalid JSON: ") + e.what());
    }
    DetectionFrame f;
    // `makeway verify` writes {"verified": [...]}: its accepted entries are detections with the
    // verified box and the existence probability as score.
    const bool verified = j.is_object() && !j.contains("detections") && j.contains("verified");
    const Json& list = j.is_object() && j.contains("detections") ? j["detections"]
                       : verified                                ? j["verified"]
                                                                 : j;
    if (!list.is_array())
        throw FormatError(
            "expected a list of detections (or {\"detections\": [...]}, or verify's {\"verified\": "
            "[...]})");
    if (j.is_object() && j.contains("stamp_s")) {
        if (!j["stamp_s"].is_number() || !std::isfinite(j["stamp_s"].get<double>()))
            throw FormatError("'stamp_s' must be a number");
        f.stamp_s = j["stamp_s"].get<double>();
    }
    if (j.is_object() && j.contains("T_world_sensor"))
        f.T_world_sensor = pose_from_json(j["T_world_sensor"], "T_world_sensor");
    for (std::size_t i = 0; i < list.size(); ++i) {
        try {
            if (!verified) {
                f.detections_sensor.push_back(detection_from_json(list[i], any_score));
                continue;
            }
            const Json& v = list[i];
            if (!v.is_object() || !v.contains("accepted") || !v["accepted"].is_boolean())
                throw FormatError("'accepted' must be true or false");
            if (!v["accepted"].get<bool>()) continue;
            if (!v.contains("p_exist")) throw FormatError("'p_exist' is missing");
            Json d = v;
            d["score"] = v["p_exist"];
            f.detections_sensor.push_back(detection_from_json(d, any_score));
        } catch (const FormatError& e) {
            throw FormatError("detection " + std::to_string(i) + ": " + e.what());
        }
    }
    return f;
}

DetectionFrame read_detection_frame(const std::filesystem::path& path, bool any_score) {
    const std::string text = read_file(path);
    try {
        return parse_detection_frame(text, any_score);
    } catch (const FormatError& e) {
        throw FileError(path.string(), e.what());
    }
}

Json to_json(const DetectionFrame& f) {
    Json dets = Json::array();
    for (const Detection& d : f.detections_sensor) {
        dets.push_back({{"class", std::string(to_string(d.cls))},
                        {"box", to_json(d.box_sensor)},
                        {"score", d.score},
                        {"class_probabilities", d.class_probabilities}});
    }
    Json j = {{"stamp_s", f.stamp_s}, {"detections", dets}};
    if (f.T_world_sensor) {
        j["T_world_sensor"] = pose_to_json(*f.T_world_sensor);
    }
    return j;
}

std::vector<ObjectEstimate> read_object_frame(const std::filesystem::path& path, double* stamp_s) {
    const Json j = read_json(path);
    if (!j.is_object() || !j.contains("objects") || !j["objects"].is_array())
        throw FileError(path.string(), "expected {\"objects\": [...]}");
    if (stamp_s != nullptr) {
        if (!j.contains("stamp_s") || !j["stamp_s"].is_number())
            throw FileError(path.string(), "'stamp_s' must be a number");
        *stamp_s = j["stamp_s"].get<double>();
    }
    std::vector<ObjectEstimate> out;
    for (std::size_t i = 0; i < j["objects"].size(); ++i) {
        const Json& o = j["objects"][i];
        try {
            ObjectEstimate e;
            if (!o.is_object() || !o.contains("id") || !o["id"].is_number_unsigned())
                throw FormatError("'id' must be a non-negative integer");
            e.id = o["id"].get<std::uint32_t>();
            if (!o.contains("class") || !o["class"].is_string() ||
                !parse_object_class(o["class"].get<std::string>())) {
                throw FormatError("'class' must be chair or table");
            }
            e.cls = *parse_object_class(o["class"].get<std::string>());
            if (!o.contains("box_world")) throw FormatError("missing 'box_world'");
            e.box_world = box_from_json(o["box_world"]);
            if (o.contains("existence") && o["existence"].is_number())
                e.existence = o["existence"].get<double>();
            out.push_back(e);
        } catch (const FormatError& e) {
            throw FileError(path.string(), "object " + std::to_string(i) + ": " + e.what());
        }
    }
    return out;
}

Json objects_to_json(int frame, double stamp_s, const std::vector<ObjectEstimate>& objects) {
    Json list = Json::array();
    for (const ObjectEstimate& o : objects) {
        list.push_back({{"id", o.id},
                        {"class", std::string(to_string(o.cls))},
                        {"box_world", to_json(o.box_world)},
                        {"velocity_mps", {o.velocity_mps.x(), o.velocity_mps.y()}},
                        {"existence", o.existence}});
    }
    return {{"frame", frame}, {"stamp_s", stamp_s}, {"objects", list}};
}

std::vector<std::filesystem::path> frame_files(const std::filesystem::path& dir,
                                               const std::string& extension) {
    if (!std::filesystem::is_directory(dir)) throw FileError(dir.string(), "not a folder");
    std::vector<std::filesystem::path> out;
    for (const auto& e : std::filesystem::directory_iterator(dir)) {
        if (e.is_regular_file() && lower_extension(e.path()) == extension) out.push_back(e.path());
    }
    std::sort(out.begin(), out.end());
    if (out.empty()) throw FileError(dir.string(), "no ." + extension + " files");
    return out;
}

std::vector<std::filesystem::path> kitti_sequence_files(const std::filesystem::path& path) {
    if (std::filesystem::is_regular_file(path)) return {path};
    return frame_files(path, "txt");
}

}  // namespace makeway::io
