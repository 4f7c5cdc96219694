// libFuzzer target: read_zones (a learned zones file) must either read or throw FileError; never
// crash, hang or leak. What it reads must stay usable: one zone coordinate near a chair.
#include <cstddef>
#include <cstdint>

#include "fuzz/fuzz_util.hpp"
#include "io/error.hpp"
#include "io/file_util.hpp"
#include "io/zones_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto& dir = makeway::fuzz::private_dir();
    try {
        makeway::io::write_file_atomic(dir / "zones.yaml",
                                       std::string_view(reinterpret_cast<const char*>(data), size));
        makeway::costmap::AffordanceParams p;
        p.learned = std::make_shared<const makeway::costmap::LearnedZones>(
            makeway::io::read_zones(dir / "zones.yaml"));
        // A raster is motions x footprint cells: kept small enough for the fuzzer's time limit.
        const auto* chair_zone = p.learned->of(makeway::ObjectClass::kChair);
        if (chair_zone != nullptr && chair_zone->motions.size() <= 2000) {
            makeway::ObjectEstimate chair;
            chair.box_world = {{0.0, 0.0, 0.45}, {0.5, 0.5, 0.9}, 0.0};
            (void)makeway::costmap::zone_coordinate(chair, p, {-0.6, 0.1});
        }
    } catch (const makeway::io::FileError&) {
    }
    return 0;
}
