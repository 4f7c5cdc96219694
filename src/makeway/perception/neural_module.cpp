#include "makeway/perception/neural_module.hpp"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <stdexcept>
#include <vector>

#include "makeway/perception/detector.hpp"

namespace makeway::perception {

namespace {

struct Module {
    std::mutex mutex;
    void* handle = nullptr;
    std::filesystem::path path;
    std::string failure;  ///< why it did not open (kept: every later use fails the same way)
    int threads = 0;      ///< set_inference_threads' count, applied when the module opens
};

Module& module() {
    static Module m;
    return m;
}

std::vector<std::filesystem::path> candidates() {
    if (const char* env = std::getenv("MAKEWAY_NEURAL_MODULE"); env != nullptr && *env != '\0')
        return {env};
    std::error_code ec;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (ec) return {kNeuralModuleFile};  // the loader's own search (LD_LIBRARY_PATH, ...)
    const std::filesystem::path bin = exe.parent_path();
    return {bin.parent_path() / "lib" / kNeuralModuleFile, bin / kNeuralModuleFile};
}

// Called with the lock held, the module open: its torch's and OpenBLAS's threads.
void apply_threads(const Module& m) {
    using SetThreads = void (*)(int);
    if (m.threads <= 0) return;
    if (auto* set = reinterpret_cast<SetThreads>(dlsym(m.handle, "makeway_neural_set_threads")))
        set(m.threads);
}

// Called with the lock held.
void open(Module& m) {
    std::string tried;
    for (const std::filesystem::path& p : candidates()) {
        std::error_code ec;
        if (p.has_parent_path() && !std::filesystem::exists(p, ec)) {
            tried += (tried.empty() ? "" : "; ") + p.string() + ": no such file";
            continue;
        }
        // RTLD_LOCAL: torch's symbols stay the module's own and never meet the program's.
        if (void* h = dlopen(p.c_str(), RTLD_NOW | RTLD_LOCAL)) {
            m.handle = h;
            m.path = p;
            apply_threads(m);
            return;
        }
        const char* why = dlerror();
        tried += (tried.empty() ? "" : "; ") + std::string(why != nullptr ? why : p.c_str());
    }
    m.failure = std::string("the networks' module ") + kNeuralModuleFile +
                " could not be loaded (" + tried +
                "): build the target makeway_neural, or set MAKEWAY_NEURAL_MODULE to its file";
}

}  // namespace

void* neural_module_symbol(const char* symbol) {
    Module& m = module();
    const std::lock_guard lock(m.mutex);
    if (m.handle == nullptr && m.failure.empty()) open(m);
    if (m.handle == nullptr) throw std::runtime_error(m.failure);
    void* s = dlsym(m.handle, symbol);
    if (s == nullptr)
        throw std::runtime_error(m.path.string() + ": no symbol " + symbol +
                                 " (a module built from other sources than this program, or "
                                 "without this network: -DMAKEWAY_SHAPE_NETWORKS=OFF leaves the "
                                 "shape networks out)");
    return s;
}

std::string neural_module_path() {
    Module& m = module();
    const std::lock_guard lock(m.mutex);
    return m.handle != nullptr ? m.path.string() : std::string();
}

void set_inference_threads(int threads) {
    if (threads <= 0) return;
    Module& m = module();
    const std::lock_guard lock(m.mutex);
    m.threads = threads;
    // Not opened for this: a program that sets the count and then runs no network never loads
    // torch. The module takes the count when it opens.
    if (m.handle != nullptr) apply_threads(m);
}

}  // namespace makeway::perception
