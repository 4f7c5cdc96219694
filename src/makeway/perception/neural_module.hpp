#pragma once
// The networks (the detector and the shape networks) live in a module of their own,
// libmakeway_neural.so, the only binary that links libtorch, opened on first use. Loading libtorch
// costs a process 0.7 s (2 s under ASan: 286 libraries and torch's operator registrations), which
// every start of the program paid when it was linked in, whether a network ran or not: `makeway
// --help`, each of the CLI tests' 176 runs, a navigation without a detector. The program holds
// facades (Detector, ShapeModel) whose Impl is the module's; the module's functions reach them
// through one table per facade (detector_backend.hpp, shape/shape_backend.hpp).
#include <cstdint>
#include <stdexcept>
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

/// The table a facade reaches the module through: what the module's function `symbol` returns,
/// checked to be of this program's interface (its `abi` and its size; `what` names it in the
/// error). Throws std::runtime_error as neural_module_symbol, or when the interface differs.
template <class Table>
const Table& neural_module_table(const char* symbol, std::uint32_t abi, const char* what) {
    using Get = const Table* (*)();
    const Table* table = reinterpret_cast<Get>(neural_module_symbol(symbol))();
    if (table->abi != abi || table->size != sizeof(Table))
        throw std::runtime_error(neural_module_path() + ": a " + what +
                                 " interface other than this program's (rebuild the target "
                                 "makeway_neural)");
    return *table;
}

}  // namespace makeway::perception
