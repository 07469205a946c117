# Precompiled headers for the targets with many translation units.
#
# Why: most of our .cpp files include Eigen (through sim/mesh/tet_mesh.hpp),
# every test file includes Catch2's single header, and the harness's files
# include nlohmann/json. Parsing them alone takes, with g++ 12 at -O3 on the
# 2-core CI machine, about 1.6 s (Eigen/Geometry), 1.3 s (catch.hpp) and
# 2.1 s (json.hpp) a translation unit, against 2.5-7 s for a whole file.
# A target's precompiled header is built once (about 6 s) and loaded by each
# of its files instead (README, "Building").
#
# Only standard and third-party headers go in, never a project header. A
# project header that forgets one of them still compiles here, but fails in a
# build with TCBENCH_PRECOMPILED_HEADERS=OFF. The sanitizer and fuzz presets
# build that way: there instrumentation, not parsing, takes the time (the
# asan build of the fast tests took 335 s with them, 340 s without).
# They change no arithmetic: the same headers are parsed with the same flags,
# once per target instead of once per file.
option(TCBENCH_PRECOMPILED_HEADERS "Precompile the standard, Eigen, Catch2 and JSON headers per target" ON)

set(TCBENCH_PCH_COMMON
  <algorithm> <array> <chrono> <cmath> <cstdint> <filesystem> <functional>
  <map> <memory> <optional> <span> <sstream> <string> <unordered_map> <vector>
  <Eigen/Core> <Eigen/Geometry>)

# tcbench_precompile_headers(<target> [EXTRA <headers...>]): the common list
# and EXTRA, precompiled for <target>'s own flags. Files compiled with other
# options than their target's (set_source_files_properties COMPILE_OPTIONS)
# must set SKIP_PRECOMPILE_HEADERS: GCC records some options in the header.
function(tcbench_precompile_headers target)
  if(NOT TCBENCH_PRECOMPILED_HEADERS)
    return()
  endif()
  cmake_parse_arguments(ARG "" "" "EXTRA" ${ARGN})
  target_precompile_headers(${target} PRIVATE ${TCBENCH_PCH_COMMON} ${ARG_EXTRA})
endfunction()
