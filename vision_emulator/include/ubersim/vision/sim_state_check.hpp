#pragma once
// Content checks on a decoded SIM_STATE. LCM only guarantees the bytes decode;
// a broken publisher can still send NaN positions, a negative step or a team
// that does not exist. Such a state is skipped whole (the next one comes a
// physics step later) so nothing non-finite ever reaches a frame.
#include <string>
#include <ubersim/field_geometry_t.hpp>
#include <ubersim/sim_state_t.hpp>

namespace ubersim::vision {

// Empty when the state can be used, else what is wrong with it.
std::string find_sim_state_problem(const sim_state_t& state);
// Empty when the geometry can be used, else what is wrong with it.
std::string find_field_geometry_problem(const field_geometry_t& geometry);

}  // namespace ubersim::vision
