#pragma once
// Seeds of the LCM fuzz targets: real messages of every type, as the
// simulator's processes send them (see lcm_seeds.cpp).
#include <filesystem>

namespace ubersim::fuzz {

// Writes the seeds of fuzz_lcm_decode, fuzz_lcm_physics, fuzz_lcm_emulators
// and fuzz_lcm_consumers.
void write_lcm_seeds(const std::filesystem::path& decode_dir,
                     const std::filesystem::path& physics_dir,
                     const std::filesystem::path& emulators_dir,
                     const std::filesystem::path& consumers_dir);

}  // namespace ubersim::fuzz
