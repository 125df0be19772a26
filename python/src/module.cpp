// The ubersim Python module's compiled part (ubersim._ubersim): Sim and
// VectorSim over the in-process cores, numpy arrays in and out
// (docs/python.md). The Python package (python/ubersim/) re-exports them.
#include <ode/ode.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <spdlog/sinks/stdout_color_sinks.h>

#include <cmath>
#include <cstdlib>
#include <optional>
#include <string>
#include <thread>

#include "arrays.hpp"
#include "in_process_sim.hpp"
#include "ubersim/config.hpp"
#include "ubersim/config_paths.hpp"
#include "ubersim/field_side.hpp"
#include "ubersim/robot_config.hpp"
#include "ubersim/spdlog.hpp"
#include "vector_sim.hpp"

namespace ubersim::python {
namespace {

// The config folder a Sim uses when given none: UBERSIM_CONFIG_DIR, else the
// one the package ships (set by ubersim/__init__.py), else the build's.
std::string g_package_config_dir;

std::string config_dir_or_default(const std::optional<std::string>& given) {
  if (given) return *given;
  const char* env = std::getenv("UBERSIM_CONFIG_DIR");
  if ((env == nullptr || *env == '\0') && !g_package_config_dir.empty()) {
    return g_package_config_dir;
  }
  return default_config_dir().string();
}

// NumPy's bool_ (older NumPy gives it an __index__): a truth value, not a team.
bool is_numpy_bool(const py::handle& value) {
  return py::hasattr(value, "dtype") &&
         py::str(value.attr("dtype").attr("kind")).cast<std::string>() == "b";
}

// The one reading of a team in the module: exactly "yellow", "blue", 0 or 1
// (a Python or NumPy integer). Anything else (e.g. "Blue", "y", 1.0, True) is
// a ValueError, never a guess.
Team team_from(const py::handle& value) {
  if (py::isinstance<py::str>(value)) {
    const auto text = value.cast<std::string>();
    if (text == "yellow") return Team::Yellow;
    if (text == "blue") return Team::Blue;
  } else if (!py::isinstance<py::bool_>(value) && !py::isinstance<py::float_>(value) &&
             !is_numpy_bool(value) && PyIndex_Check(value.ptr()) != 0) {
    const py::object index = py::reinterpret_steal<py::object>(PyNumber_Index(value.ptr()));
    if (!index) {
      PyErr_Clear();  // e.g. NumPy's bool_: not a team either
    } else {
      const long code = index.cast<long>();
      if (code == 0 || code == 1) return static_cast<Team>(code);
    }
  }
  throw py::value_error("team must be 'yellow', 'blue', 0 or 1, got " +
                        py::repr(value).cast<std::string>());
}

double finite(double value, const char* name) {
  if (!std::isfinite(value)) {
    throw py::value_error(std::string(name) + " must be a finite number, got " +
                          std::to_string(value));
  }
  return value;
}

referee::FieldSides sides_from(const std::string& yellow_defends) {
  referee::FieldSides sides;
  sides.yellow_defends = parse_defended_side(yellow_defends);  // ValueError for another word
  return sides;
}

SimOptions options_from(const std::string& scenario, const std::optional<std::string>& vision,
                        const std::optional<std::string>& radio, std::uint64_t seed, double step,
                        const std::optional<std::string>& field, const std::string& physics,
                        const std::optional<std::string>& config_dir) {
  SimOptions options;
  options.scenario = scenario;
  options.vision_profile = vision.value_or("");
  options.radio_profile = radio.value_or("");
  options.seed = seed;
  options.step = step;
  options.field = field.value_or("");
  options.physics = physics;
  options.config_dir = config_dir_or_default(config_dir);
  return options;
}

// The ball as (x, y), (x, y, vx, vy) or (x, y, z, vx, vy, vz), teleported.
void put_ball(sim_control_t& request, const py::handle& ball) {
  const auto values = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(ball);
  if (!values || values.ndim() != 1 ||
      (values.shape(0) != 2 && values.shape(0) != 4 && values.shape(0) != 6)) {
    throw py::value_error("ball must be (x, y), (x, y, vx, vy) or (x, y, z, vx, vy, vz)");
  }
  const double* v = values.data();
  for (py::ssize_t k = 0; k < values.shape(0); ++k) finite(v[k], "every ball value");
  request.has_ball = true;
  request.ball.mode = ball_placement_t::TELEPORT;
  request.ball.position[0] = v[0];
  request.ball.position[1] = v[1];
  if (values.shape(0) == 4) {
    request.ball.linear_velocity[0] = v[2];
    request.ball.linear_velocity[1] = v[3];
  } else if (values.shape(0) == 6) {
    request.ball.position[2] = v[2];
    for (int k = 0; k < 3; ++k) request.ball.linear_velocity[k] = v[3 + k];
  }
}

// robots: (n, 5) rows of team, id, x, y, orientation (rad), all of type `type`.
void put_robots(sim_control_t& request, const py::handle& robots, const std::string& type) {
  const auto rows = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(robots);
  if (!rows || rows.ndim() != 2 || rows.shape(1) != 5) {
    throw py::value_error("robots must have shape (n, 5): team, id, x, y, orientation");
  }
  for (py::ssize_t i = 0; i < rows.shape(0); ++i) {
    const double* r = rows.data() + i * 5;
    for (int k = 0; k < 5; ++k) finite(r[k], "every robots value");
    robot_placement_t p{};
    if (r[0] != std::floor(r[0]) || r[1] != std::floor(r[1])) {
      throw py::value_error("robots row " + std::to_string(i) + ": team and id must be whole");
    }
    p.team = static_cast<std::int8_t>(team_from(py::int_(static_cast<long>(r[0]))));
    p.robot_id = static_cast<std::int32_t>(r[1]);
    p.robot_type = type;
    p.present = true;
    p.x = r[2];
    p.y = r[3];
    p.orientation = r[4];
    request.robots.push_back(p);
  }
  request.num_robots = static_cast<std::int32_t>(request.robots.size());
}

py::dict reset_sim(InProcessSim& sim, std::optional<std::uint64_t> seed, const py::object& robots,
                   const py::object& ball, const std::optional<std::string>& robot_type) {
  // Check the placements before anything changes.
  sim_control_t request{};
  if (!robots.is_none()) put_robots(request, robots, robot_type.value_or(sim.default_robot_type()));
  if (!ball.is_none()) put_ball(request, ball);
  sim.reset(seed);
  if (!robots.is_none() || !ball.is_none()) sim.place(request, !robots.is_none());
  return truth_dict(sim.truth());
}

py::dict field_dict(const field_geometry_t& g) {
  py::dict d;
  d["name"] = g.name;
  d["field_length"] = g.field_length;
  d["field_width"] = g.field_width;
  d["boundary_width"] = g.boundary_width;
  d["boundary_width_goal_line"] = g.boundary_width_goal_line;
  d["line_width"] = g.line_width;
  d["goal_width"] = g.goal_width;
  d["goal_depth"] = g.goal_depth;
  d["goal_height"] = g.goal_height;
  d["goal_wall_thickness"] = g.goal_wall_thickness;
  d["wall_height"] = g.wall_height;
  d["wall_thickness"] = g.wall_thickness;
  d["center_circle_radius"] = g.center_circle_radius;
  d["penalty_area_depth"] = g.penalty_area_depth;
  d["penalty_area_width"] = g.penalty_area_width;
  d["penalty_mark_distance"] = g.penalty_mark_distance;
  d["ball_radius"] = g.ball_radius;
  return d;
}

py::dict counters_dict(const InProcessSim& sim) {
  py::dict d;
  const physics::WorldCounters& w = sim.world().counters();
  d["commands_applied"] = w.commands_applied;
  d["commands_dropped"] = w.commands_dropped;
  d["commands_clamped"] = w.commands_clamped.commands;
  d["bodies_reset"] = w.bodies_reset;
  d["robots_set_upright"] = w.robots_set_upright;
  d["kicks"] = w.kicks;
  if (const vision::VisionEmulator* v = sim.vision()) {
    d["vision_frames_captured"] = v->stats().frames_captured;
    d["vision_frames_published"] = v->stats().frames_published;
  }
  if (const radio::RadioEmulator* r = sim.radio()) {
    for (Team team : kTeams) {
      const radio::TeamReport report = r->report(team);
      const std::string prefix = std::string("radio_") + team_name(team) + "_";
      std::uint64_t rejected = 0;
      for (std::uint64_t count : report.problems) rejected += count;
      d[(prefix + "packets_received").c_str()] = report.packets_received;
      d[(prefix + "packets_rejected_entries").c_str()] = rejected;
      d[(prefix + "packets_superseded").c_str()] = report.commands.superseded;
      d[(prefix + "packets_lost").c_str()] = report.commands.lost_packets;
      d[(prefix + "entries_lost").c_str()] = report.commands.lost_entries;
      d[(prefix + "feedback_lost").c_str()] = report.feedback.lost_packets;
    }
  }
  return d;
}

// A robot type's parameters that learners and rSim's field parameters need.
py::dict robot_type_dict(const InProcessSim& sim, const std::optional<std::string>& name) {
  const auto type = sim.world().setup().robot_types(name.value_or(sim.default_robot_type()));
  py::dict d;
  d["name"] = type->name;
  d["drive"] = enum_name(type->drive, kDriveKindNames);
  d["radius"] = type->radius;
  d["height"] = type->height;
  d["front_distance"] = type->front_distance;
  d["kicker_distance"] = type->kicker_distance;
  d["kicker_width"] = type->kicker_width;
  py::list angles;
  for (const WheelConfig& wheel : type->wheels) angles.append(wheel.angle);
  d["wheel_angles"] = angles;  // rad
  d["wheel_radius"] = type->wheel_radius;
  d["motor_max_speed"] = type->motor_max_speed;  // rad/s at the wheel
  d["max_speed"] = type->max_speed;
  d["max_angular_speed"] = type->max_angular_speed;
  d["max_acceleration"] = type->max_acceleration;
  d["kick_max_speed"] = type->kick_max_speed;
  d["chip_max_speed"] = type->chip_max_speed;
  d["chip_default_angle"] = type->chip_default_angle;
  d["dribbler_max_speed"] = type->dribbler_max_speed;
  return d;
}

// One referee situation, from Python's arguments.
void set_situation(InProcessSim& sim, referee::Situation kind, const py::object& team, double x,
                   double y, const std::string& yellow_defends) {
  referee::SituationRequest request;
  request.kind = kind;
  if (!team.is_none()) request.team = team_from(team);
  request.x = finite(x, "x");
  request.y = finite(y, "y");
  sim.situation(request, sides_from(yellow_defends));
}

// Sim: robots and the ball put where the caller says.
void bind_sim_placements(py::class_<InProcessSim>& sim_class) {
  using namespace pybind11::literals;
  sim_class
      .def(
          "place_robot",
          [](InProcessSim& sim, const py::object& team, int id, double x, double y,
             double orientation, double vx, double vy, double omega,
             const std::optional<std::string>& robot_type) {
            sim_control_t request{};
            robot_placement_t p{};
            p.team = static_cast<std::int8_t>(team_from(team));
            p.robot_id = id;
            p.present = true;
            const bool known = sim.wheel_count(team_from(team), id).has_value();
            p.robot_type = robot_type.value_or(known ? "" : sim.default_robot_type());
            p.x = x;
            p.y = y;
            p.orientation = orientation;
            p.vx = vx;
            p.vy = vy;
            p.omega = omega;
            request.robots.push_back(p);
            request.num_robots = 1;
            sim.place(request, false);
          },
          "team"_a, "id"_a, "x"_a, "y"_a, "orientation"_a = 0.0, "vx"_a = 0.0, "vy"_a = 0.0,
          "omega"_a = 0.0, "robot_type"_a = py::none())
      .def(
          "remove_robot",
          [](InProcessSim& sim, const py::object& team, int id) {
            sim_control_t request{};
            robot_placement_t p{};
            p.team = static_cast<std::int8_t>(team_from(team));
            p.robot_id = id;
            p.present = false;
            request.robots.push_back(p);
            request.num_robots = 1;
            sim.place(request, false);
          },
          "team"_a, "id"_a)
      .def(
          "place_ball",
          [](InProcessSim& sim, double x, double y, double z, double vx, double vy, double vz) {
            sim_control_t request{};
            put_ball(request, py::cast(std::vector<double>{x, y, z, vx, vy, vz}));
            sim.place(request, false);
          },
          "x"_a, "y"_a, "z"_a = 0.0, "vx"_a = 0.0, "vy"_a = 0.0, "vz"_a = 0.0);
}

// Sim: the referee situations, placed as the automatic referee places them.
void bind_sim_situations(py::class_<InProcessSim>& sim_class) {
  using namespace pybind11::literals;
  sim_class
      .def(
          "kickoff",
          [](InProcessSim& sim, const py::object& team, const std::string& yellow_defends) {
            set_situation(sim, referee::Situation::KickOff, team, 0, 0, yellow_defends);
          },
          "team"_a, "yellow_defends"_a = "negative")
      .def(
          "free_kick",
          [](InProcessSim& sim, const py::object& team, double x, double y,
             const std::string& yellow_defends) {
            set_situation(sim, referee::Situation::FreeKick, team, x, y, yellow_defends);
          },
          "team"_a, "x"_a, "y"_a, "yellow_defends"_a = "negative")
      .def(
          "penalty",
          [](InProcessSim& sim, const py::object& team, const std::string& yellow_defends) {
            set_situation(sim, referee::Situation::Penalty, team, 0, 0, yellow_defends);
          },
          "team"_a, "yellow_defends"_a = "negative")
      .def(
          "ball_placement",
          [](InProcessSim& sim, double x, double y, const std::string& yellow_defends) {
            set_situation(sim, referee::Situation::BallPlacement, py::none(), x, y, yellow_defends);
          },
          "x"_a, "y"_a, "yellow_defends"_a = "negative")
      .def(
          "stop",
          [](InProcessSim& sim, const std::string& yellow_defends) {
            set_situation(sim, referee::Situation::Stop, py::none(), 0, 0, yellow_defends);
          },
          "yellow_defends"_a = "negative");
}

// Sim: counters, robot types and read-only properties.
void bind_sim_properties(py::class_<InProcessSim>& sim_class) {
  using namespace pybind11::literals;
  sim_class.def("counters", &counters_dict)
      .def("robot_type_info", &robot_type_dict, "name"_a = py::none(),
           "A robot type's parameters (SI units, angles in rad); the scenario's type by default.")
      .def_property_readonly("field",
                             [](const InProcessSim& s) { return field_dict(s.geometry()); })
      .def_property_readonly("time", &InProcessSim::time)
      .def_property_readonly("dt", [](const InProcessSim& s) { return s.world().dt(); })
      .def_property_readonly("step_length", [](const InProcessSim& s) { return s.options().step; })
      .def_property_readonly("seed", &InProcessSim::seed)
      .def_property_readonly("scenario", [](const InProcessSim& s) { return s.options().scenario; })
      .def_property_readonly("vision_emulated", &InProcessSim::vision_emulated)
      .def_property_readonly("radio_emulated", &InProcessSim::radio_emulated)
      .def_property_readonly("robot_type", &InProcessSim::default_robot_type);
}

void bind_sim(py::module_& m) {
  using namespace pybind11::literals;
  py::class_<InProcessSim> sim_class(m, "Sim",
                                     "One simulated world in this process (docs/python.md).");
  sim_class
      .def(py::init([](const std::string& scenario, const std::optional<std::string>& vision,
                       const std::optional<std::string>& radio, std::uint64_t seed, double step,
                       const std::optional<std::string>& field, const std::string& physics,
                       const std::optional<std::string>& config_dir) {
             return std::make_unique<InProcessSim>(
                 options_from(scenario, vision, radio, seed, step, field, physics, config_dir));
           }),
           "scenario"_a = "division_b_6v6", "vision_profile"_a = py::none(),
           "radio_profile"_a = py::none(), "seed"_a = 0, "step"_a = 0.025, "field"_a = py::none(),
           "physics"_a = "default", "config_dir"_a = py::none())
      .def("reset", &reset_sim, "seed"_a = py::none(), "robots"_a = py::none(),
           "ball"_a = py::none(), "robot_type"_a = py::none(),
           "Back to the scenario at sim time 0 (robots (n, 5): team, id, x, y, orientation "
           "replace its robots; ball: (x, y[, vx, vy]) or (x, y, z, vx, vy, vz)); returns the "
           "ground truth.")
      .def(
          "step",
          [](InProcessSim& sim, const py::object& commands) {
            const std::vector<RobotOrder> orders = orders_from_array(commands, sim, "");
            {
              py::gil_scoped_release release;
              sim.step(orders);
            }
            return step_dict(sim.last_output());
          },
          "commands"_a = py::none(),
          "Sends the commands (n, 14; ubersim.COMMAND_COLUMNS) and advances one step; returns "
          "ground truth, the vision frames and the radio feedback of the step.")
      .def("truth", [](InProcessSim& sim) { return truth_dict(sim.truth()); });
  bind_sim_placements(sim_class);
  bind_sim_situations(sim_class);
  bind_sim_properties(sim_class);
}

// VectorSim.step's commands: None, or one entry (array or None) per world.
std::vector<std::vector<RobotOrder>> orders_for_worlds(VectorSim& sims,
                                                       const py::object& commands) {
  std::vector<std::vector<RobotOrder>> orders(sims.size());
  if (commands.is_none()) return orders;
  if (!py::isinstance<py::sequence>(commands) && !py::isinstance<py::array>(commands)) {
    throw py::type_error("commands must be None or one commands array per world");
  }
  const py::sequence per_world = commands.cast<py::sequence>();
  if (per_world.size() != sims.size()) {
    throw py::value_error("commands must have one entry per world: " + std::to_string(sims.size()) +
                          " worlds, got " + std::to_string(per_world.size()));
  }
  for (std::size_t i = 0; i < sims.size(); ++i) {
    orders[i] = orders_from_array(per_world[i], sims.world(i), "world " + std::to_string(i) + ": ");
  }
  return orders;
}

// Stacks the worlds' truth: robots (n, m, 14), padded with NaN rows when
// worlds have fewer robots than the most; ball (n, 6); time (n,).
py::dict stacked_truth(VectorSim& sims, bool with_step_output) {
  std::size_t most = 0;
  for (std::size_t i = 0; i < sims.size(); ++i) {
    most = std::max(most, sims.world(i).last_output().truth.robots.size());
  }
  const std::size_t columns = kRobotColumns.size();
  py::array_t<double> robots({sims.size(), most, columns});
  py::array_t<double> balls({sims.size(), kBallColumns.size()});
  py::array_t<double> times(static_cast<py::ssize_t>(sims.size()));
  py::list vision, frames, feedback;
  double* r = robots.mutable_data();
  std::fill(r, r + robots.size(), std::nan(""));
  for (std::size_t i = 0; i < sims.size(); ++i) {
    const StepOutput& out = sims.world(i).last_output();
    const auto own = robots_array(out.truth);
    std::copy(own.data(), own.data() + own.size(), r + i * most * columns);
    const auto ball = ball_array(out.truth);
    std::copy(ball.data(), ball.data() + ball.size(),
              balls.mutable_data() + i * kBallColumns.size());
    times.mutable_data()[i] = out.truth.sim_time;
    if (with_step_output) {
      vision.append(detections_array(out.frames));
      frames.append(frames_array(out.frames));
      feedback.append(feedback_array(out.feedback));
    }
  }
  py::dict d;
  d["time"] = times;
  d["robots"] = robots;
  d["ball"] = balls;
  if (with_step_output) {
    d["vision"] = vision;
    d["frames"] = frames;
    d["feedback"] = feedback;
  }
  return d;
}

void bind_vector_sim(py::module_& m) {
  using namespace pybind11::literals;
  py::class_<VectorSim>(m, "VectorSim",
                        "n worlds stepped together on C++ threads (docs/python.md).")
      .def(py::init([](std::size_t n, const std::string& scenario,
                       const std::optional<std::string>& vision,
                       const std::optional<std::string>& radio, std::uint64_t seed,
                       const std::optional<std::vector<std::uint64_t>>& seeds, double step,
                       std::size_t threads, const std::optional<std::string>& field,
                       const std::string& physics, const std::optional<std::string>& config_dir) {
             if (n < 1) throw py::value_error("n must be at least 1");
             std::vector<std::uint64_t> world_seeds;
             if (seeds) {
               if (seeds->size() != n) throw py::value_error("seeds must have one seed per world");
               world_seeds = *seeds;
             } else {
               for (std::size_t i = 0; i < n; ++i) world_seeds.push_back(seed + i);
             }
             const SimOptions options =
                 options_from(scenario, vision, radio, seed, step, field, physics, config_dir);
             py::gil_scoped_release release;
             auto sims = std::make_unique<VectorSim>(options, world_seeds, threads);
             for (std::size_t i = 0; i < sims->size(); ++i) sims->world(i).truth();
             return sims;
           }),
           "n"_a, "scenario"_a = "division_b_6v6", "vision_profile"_a = py::none(),
           "radio_profile"_a = py::none(), "seed"_a = 0, "seeds"_a = py::none(), "step"_a = 0.025,
           "threads"_a = 0, "field"_a = py::none(), "physics"_a = "default",
           "config_dir"_a = py::none())
      .def(
          "step",
          [](VectorSim& sims, const py::object& commands) {
            const auto orders = orders_for_worlds(sims, commands);
            {
              py::gil_scoped_release release;
              sims.step(orders);
            }
            return stacked_truth(sims, true);
          },
          "commands"_a = py::none(),
          "Steps every world with its commands (a list of n arrays or None); returns stacked "
          "ground truth and per-world lists of vision, frames and feedback.")
      .def(
          "reset",
          [](VectorSim& sims, const std::optional<std::vector<std::size_t>>& worlds,
             const std::optional<std::vector<std::optional<std::uint64_t>>>& seeds) {
            std::vector<std::size_t> which;
            if (worlds) {
              which = *worlds;
            } else {
              for (std::size_t i = 0; i < sims.size(); ++i) which.push_back(i);
            }
            const auto world_seeds =
                seeds ? *seeds : std::vector<std::optional<std::uint64_t>>(which.size());
            {
              py::gil_scoped_release release;
              sims.reset(which, world_seeds);
              for (std::size_t i : which) sims.world(i).truth();
            }
            return stacked_truth(sims, false);
          },
          "worlds"_a = py::none(), "seeds"_a = py::none(),
          "Resets the worlds named (all when None), each with its seed or its own; returns the "
          "stacked ground truth of every world.")
      .def("__len__", &VectorSim::size)
      .def(
          "__getitem__",
          [](VectorSim& sims, std::size_t i) -> InProcessSim& {
            if (i >= sims.size()) throw py::index_error("no world " + std::to_string(i));
            return sims.world(i);
          },
          py::return_value_policy::reference_internal)
      .def_property_readonly("threads", &VectorSim::threads);
}

// For the tests: ODE's random seed is per thread (physics/model/src/ode_random.cpp),
// as seen from inside this module, where libode is loaded by Python.
bool ode_random_is_per_thread() {
  dRandSetSeed(3);
  unsigned long other_seed = 0;
  std::thread other([&] {
    dRandSetSeed(7);
    for (int i = 0; i < 10; ++i) dRandInt(1000);
    other_seed = dRandGetSeed();
  });
  other.join();
  return dRandGetSeed() == 3 && other_seed != 7;
}

}  // namespace
}  // namespace ubersim::python

PYBIND11_MODULE(_ubersim, m) {
  using namespace ubersim::python;
  m.doc() =
      "ubersim's worlds in this process: physics, vision and radio emulation (docs/python.md)";
  // Physics and the emulators log through spdlog: warnings and errors only,
  // on stderr (stdout belongs to the caller's program).
  spdlog::set_default_logger(spdlog::stderr_color_mt("ubersim"));
  spdlog::set_level(spdlog::level::warn);
  py::register_exception_translator([](std::exception_ptr error) {
    try {
      if (error) std::rethrow_exception(error);
    } catch (const ubersim::ConfigError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });
  m.attr("COMMAND_COLUMNS") = column_names(kCommandColumns);
  m.attr("ROBOT_COLUMNS") = column_names(kRobotColumns);
  m.attr("BALL_COLUMNS") = column_names(kBallColumns);
  m.attr("DETECTION_COLUMNS") = column_names(kDetectionColumns);
  m.attr("FRAME_COLUMNS") = column_names(kFrameColumns);
  m.attr("FEEDBACK_COLUMNS") = column_names(kFeedbackColumns);
  m.def("_set_package_config_dir", [](const std::string& dir) { g_package_config_dir = dir; });
  m.def("default_config_dir", [] { return config_dir_or_default(std::nullopt); });
  m.def(
      "_team_code", [](const py::handle& team) { return static_cast<int>(team_from(team)); },
      py::arg("team"), "0 for 'yellow' or 0, 1 for 'blue' or 1; anything else raises ValueError.");
  m.def("_ode_random_is_per_thread", &ode_random_is_per_thread);
  bind_sim(m);
  bind_vector_sim(m);
}
