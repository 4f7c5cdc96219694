# Every outside library comes from Debian's packages (scripts/install-deps.sh installs them).
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(Threads REQUIRED)
find_package(yaml-cpp REQUIRED)
find_package(nlohmann_json 3.10 REQUIRED)
find_package(assimp REQUIRED)
find_package(embree 3 REQUIRED)
find_package(TBB REQUIRED)
find_package(tsl-robin-map REQUIRED)  # the odometry's voxel map
# libtorch (the detector); Debian's libtorch-dev ships TorchConfig.cmake. The fuzz build (clang 14)
# builds parsers only: torch 1.13's headers do not compile with clang 14 in C++20.
if(NOT MAKEWAY_FUZZ)
    find_package(Torch REQUIRED)
endif()

# liblzf (PCD binary_compressed) ships no CMake config.
find_path(LZF_INCLUDE_DIR lzf.h PATH_SUFFIXES liblzf REQUIRED)
find_library(LZF_LIBRARY lzf REQUIRED)
add_library(lzf::lzf UNKNOWN IMPORTED)
set_target_properties(lzf::lzf PROPERTIES IMPORTED_LOCATION ${LZF_LIBRARY}
                                          INTERFACE_INCLUDE_DIRECTORIES ${LZF_INCLUDE_DIR})

if(MAKEWAY_BUILD_APPS)
    find_package(CLI11 REQUIRED)
endif()
if(MAKEWAY_BUILD_TESTS)
    find_package(GTest REQUIRED)
    include(GoogleTest)
endif()
if(MAKEWAY_BUILD_BENCH)
    find_package(benchmark REQUIRED)
endif()

find_package(PkgConfig REQUIRED)
pkg_check_modules(CAIRO REQUIRED IMPORTED_TARGET cairo)
# libzip: model files are checked before torch reads them (its CMake config needs the zip tools).
pkg_check_modules(LIBZIP REQUIRED IMPORTED_TARGET libzip)

# The bag preflight (ros/bag_check.cpp) inflates compressed chunks itself: bzip2 and rosbag's lz4
# framing, both packages rosbag_storage depends on (so also in the fuzz build, which compiles it).
find_package(BZip2 REQUIRED)
find_library(ROS_LZ4_LIBRARY roslz4 REQUIRED)
add_library(makeway_bag_codecs INTERFACE)
target_link_libraries(makeway_bag_codecs INTERFACE BZip2::BZip2 ${ROS_LZ4_LIBRARY})

# ROS 1 bags (Debian's ros packages, no catkin): rosbag_storage's config, the message headers (in
# /usr/include, header-only) and ros::Time. The messages' own CMake configs need catkin: not used.
# Not in the fuzz build (clang 14 parsers only).
if(NOT MAKEWAY_FUZZ)
    # Debian's ROS configs run Python helpers that need the system interpreter's ament_package: a
    # python3 earlier on PATH (a virtualenv, pyenv) would not have it.
    if(NOT Python3_EXECUTABLE AND EXISTS /usr/bin/python3)
        set(Python3_EXECUTABLE /usr/bin/python3 CACHE FILEPATH "Debian's Python (ROS 1 CMake configs)")
    endif()
    find_package(rosbag_storage REQUIRED)
    find_library(ROS_ROSTIME_LIBRARY rostime REQUIRED)
    find_library(ROS_SERIALIZATION_LIBRARY roscpp_serialization REQUIRED)
    find_library(ROS_CPP_COMMON_LIBRARY cpp_common REQUIRED)
    find_library(ROS_CONSOLE_BRIDGE_LIBRARY console_bridge REQUIRED)  # rosbag's console, captured
    find_path(ROS_SENSOR_MSGS_INCLUDE_DIR sensor_msgs/PointCloud2.h REQUIRED)
    add_library(makeway_ros_bag_deps INTERFACE)
    target_include_directories(makeway_ros_bag_deps SYSTEM INTERFACE ${rosbag_storage_INCLUDE_DIRS} ${ROS_SENSOR_MSGS_INCLUDE_DIR})
    target_link_libraries(makeway_ros_bag_deps INTERFACE makeway_bag_codecs ${rosbag_storage_LIBRARIES} ${ROS_ROSTIME_LIBRARY}
                                                         ${ROS_SERIALIZATION_LIBRARY} ${ROS_CPP_COMMON_LIBRARY} ${ROS_CONSOLE_BRIDGE_LIBRARY})
endif()# roscpp (the node) is found in ros/CMakeLists.txt: its config adds compile definitions to the
# directory it is found in, which would recompile everything when `make ros` turns the node on.
