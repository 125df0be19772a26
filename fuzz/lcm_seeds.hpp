#pragma once
// Seeds of the LCM fuzz targets: real messages of every type, as the
// simulator's processes send them (see lcm_seeds.cpp).
#include <filesystem>

namespace ubersim::fuzz {

// Writes fuzz_lcm_decode's seeds into decode_dir and fuzz_lcm_physics's into physics_dir.
void write_lcm_seeds(const std::filesystem::path& decode_dir,
                     const std::filesystem::path& physics_dir);

}  // namespace ubersim::fuzz
