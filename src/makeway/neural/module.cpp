// The networks' module's exports: one table per facade (perception/detector_backend.hpp,
// shape/shape_backend.hpp) and the threads. Everything else in the module is hidden: its copies of
// the makeway libraries it links stay its own (-Wl,--exclude-libs,ALL, neural/CMakeLists.txt).
#include "makeway/neural/networks.hpp"

#define MAKEWAY_NEURAL_EXPORT extern "C" __attribute__((visibility("default")))

MAKEWAY_NEURAL_EXPORT const makeway::perception::DetectorBackend* makeway_detector_backend() {
    using namespace makeway::perception;
    static const DetectorBackend backend{
        .create = create_torch_detector,
        .load = load_torch_detector,
        .train = train_torch_detector,
    };
    return &backend;
}

#ifdef MAKEWAY_SHAPE_NETWORKS  // off: the detector alone (neural/CMakeLists.txt)
MAKEWAY_NEURAL_EXPORT const makeway::shape::ShapeBackend* makeway_shape_backend() {
    using namespace makeway::shape;
    static const ShapeBackend backend{
        .create = create_torch_shape_model,
        .load = load_torch_shape_model,
        .train = train_torch_shape_model,
    };
    return &backend;
}
#endif

MAKEWAY_NEURAL_EXPORT void makeway_neural_set_threads(int threads) {
    makeway::perception::set_torch_threads(threads);
}
