// makeway: the command-line front end. Parses options (CLI11) and calls one run_* per subcommand.
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>

#include "apps/commands.hpp"
#include "io/error.hpp"

namespace {

using namespace makeway::apps;

void add_info(CLI::App& app, InfoOptions& o) {
    auto* sub = app.add_subcommand("info", "Print one JSON object describing a point-cloud file: "
                                           "format, encoding, point count, fields, bounds [m], "
                                           "count of points with NaN/inf coordinates");
    sub->add_option("FILE", o.path, "Point cloud (.pcd, .ply, or KITTI .bin)")->required();
}

void add_convert(CLI::App& app, ConvertOptions& o) {
    auto* sub = app.add_subcommand("convert", "Convert a point cloud between PCD, PLY and KITTI .bin "
                                              "by file extension, keeping every field both hold");
    sub->add_option("IN", o.input, "Input cloud (.pcd, .ply, .bin)")->required();
    sub->add_option("OUT", o.output, "Output cloud (.pcd, .ply, .bin); written atomically")->required();
    sub->add_option("--pcd-encoding", o.pcd_encoding, "PCD DATA encoding")
        ->check(CLI::IsMember({"ascii", "binary", "binary_compressed"}))
        ->capture_default_str();
    sub->add_option("--ply-encoding", o.ply_encoding, "PLY encoding (binary = little endian)")
        ->check(CLI::IsMember({"ascii", "binary"}))
        ->capture_default_str();
    sub->add_option("--non-finite", o.non_finite,
                    "Points with NaN/inf coordinates: reject the file, keep them, or drop them")
        ->check(CLI::IsMember({"reject", "keep", "drop"}))
        ->capture_default_str();
}

void add_demo(CLI::App& app, DemoOptions& o) {
    auto* sub = app.add_subcommand("demo", "Run the longest end-to-end path that exists on the "
                                           "built-in default scene and write its outputs");
    sub->add_option("--config", o.config, "YAML configuration (default: built-in defaults; see "
                                          "config/default.yaml)");
    sub->add_option("--out", o.out_dir, "Output folder")->capture_default_str();
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"makeway: object-aware affordance costmaps for proactive indoor navigation "
                 "with a 3D LiDAR"};
    app.set_version_flag("--version", "makeway 0.1.0");
    app.require_subcommand(1);
    InfoOptions info;
    ConvertOptions convert;
    DemoOptions demo;
    add_info(app, info);
    add_convert(app, convert);
    add_demo(app, demo);
    if (argc > 1 && argv[1][0] != '-') {
        bool known = false;
        for (const CLI::App* sub : app.get_subcommands({})) known |= sub->get_name() == argv[1];
        if (!known) {
            print_error(std::string("unknown subcommand '") + argv[1] + "' (see makeway --help)");
            return kExitBadInput;
        }
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        print_error(e.what());
        return kExitBadInput;
    }
    try {
        if (app.got_subcommand("info")) return run_info(info);
        if (app.got_subcommand("convert")) return run_convert(convert);
        if (app.got_subcommand("demo")) return run_demo(demo);
    } catch (const makeway::io::FileError& e) {
        print_error(e.what());
        return kExitBadInput;
    } catch (const std::exception& e) {
        print_error(std::string("internal error: ") + e.what());
        return 1;
    }
    return 1;
}
