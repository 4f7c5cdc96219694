#pragma once
// The networks (the detector and the shape networks) live in a module of their own,
// libmakeway_neural.so, the only binary that links libtorch, opened on first use. Loading libtorch
// costs a process 0.7 s (2 s under ASan: 286 libraries and torch's operator registrations), which
// every start of the program paid when it was linked in, whether a network ran or not: `makeway
// --help`, each of the CLI tests' 176 runs, a navigation without a detector. The program holds
// facades (Detector, ShapeModel) whose Impl is the module's; the module's functions reach them
// through one table per facade (detector_backend.hpp, shape/shape_backend.hpp).
#include <string>

namespace makeway::perception {

/// The module's file name.
inline constexpr const char* kNeuralModuleFile = "libmakeway_neural.so";

/// The address of `symbol` in the module, which is opened on the first call (under a lock): the
/// file named by $MAKEWAY_NEURAL_MODULE when that is set, else lib/libmakeway_neural.so beside the
/// program's folder (bin/../lib: the build tree and an installed prefix), else the program's own
/// folder. Throws std::runtime_error naming each file tried and why it did not load.
void* neural_module_symbol(const char* symbol);

/// The file the module was opened from; empty while it is not open.
std::string neural_module_path();

}  // namespace makeway::perception
