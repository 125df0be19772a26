# Every external dependency is found here, once, and exposed as an imported
# target. Debian 12 ships LCM 1.3.1, which has a pkg-config file but no CMake
# package; a newer LCM (>= 1.4) ships lcmConfig.cmake, which we prefer.

find_package(PkgConfig REQUIRED)

# --- LCM -> target ubersim::lcm, program LCM_GEN_EXECUTABLE, LCM_JAR ---------
find_package(lcm CONFIG QUIET)
if(TARGET lcm::lcm)
  add_library(ubersim::lcm INTERFACE IMPORTED)
  target_link_libraries(ubersim::lcm INTERFACE lcm::lcm)
  message(STATUS "LCM: CMake package ${lcm_VERSION}")
else()
  pkg_check_modules(LCM REQUIRED IMPORTED_TARGET lcm)
  add_library(ubersim::lcm INTERFACE IMPORTED)
  target_link_libraries(ubersim::lcm INTERFACE PkgConfig::LCM)
  message(STATUS "LCM: pkg-config ${LCM_VERSION}")
endif()
find_program(LCM_GEN_EXECUTABLE lcm-gen REQUIRED)
find_file(LCM_JAR lcm.jar PATHS /usr/share/java /usr/local/share/java)

# --- ODE (double precision in Debian) ------------------------------------------
pkg_check_modules(ODE REQUIRED IMPORTED_TARGET ode)
add_library(ubersim::ode INTERFACE IMPORTED)
target_link_libraries(ubersim::ode INTERFACE PkgConfig::ODE)

# --- header/library packages with CMake configs --------------------------------
# lcmtypes/gen_encoded_bounds.py writes the decode bounds at build time.
find_package(Python3 COMPONENTS Interpreter REQUIRED)
find_package(Eigen3 3.3 REQUIRED NO_MODULE)
find_package(spdlog REQUIRED)
find_package(CLI11 REQUIRED)
find_package(GTest REQUIRED)
find_package(Threads REQUIRED)
find_package(benchmark QUIET)

# --- Java, for the lcm-spy type jar (optional: only lcm-spy needs it) ----------
find_package(Java COMPONENTS Development QUIET)
if(Java_FOUND AND LCM_JAR)
  include(UseJava)
  set(UBERSIM_BUILD_JAVA ON)
else()
  set(UBERSIM_BUILD_JAVA OFF)
  message(STATUS "Java or lcm.jar not found: the lcm-spy type jar is not built")
endif()

# --- Cyclone DDS (optional bridge) ---------------------------------------------
find_package(CycloneDDS CONFIG QUIET)
if(CycloneDDS_FOUND)
  message(STATUS "Cyclone DDS ${CycloneDDS_VERSION} found: the DDS bridge can be built")
else()
  message(STATUS "Cyclone DDS not found: the DDS bridge is skipped (install cyclonedds-dev to build it)")
endif()
