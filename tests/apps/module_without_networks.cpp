// A module that loads but holds none of the networks' functions (tests/apps/CMakeLists.txt).
extern "C" __attribute__((visibility("default"))) int makeway_test_module_without_networks() {
    return 1;
}
