#include "arrays.hpp"

#include <cmath>
#include <limits>
#include <string>

namespace ubersim::python {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

enum CommandColumn {
  kTeam,
  kId,
  kMode,
  kVx,
  kVy,
  kOmega,
  kWheel0,
  kKickSpeed = kWheel0 + kMaxWheels,
  kChipSpeed,
  kChipAngle,
  kDribblerSpeed,
};
static_assert(kDribblerSpeed + 1 == static_cast<int>(kCommandColumns.size()));

py::array_t<double> matrix(std::size_t rows, std::size_t columns) {
  return py::array_t<double>({static_cast<py::ssize_t>(rows), static_cast<py::ssize_t>(columns)});
}

// A whole number in [low, high] in the given cell, else ValueError.
int whole_number(double value, int low, int high, const std::string& where) {
  if (!std::isfinite(value) || value != std::floor(value) || value < low || value > high) {
    throw py::value_error(where + " must be a whole number in " + std::to_string(low) + ".." +
                          std::to_string(high) + ", got " +
                          py::str(py::float_(value)).cast<std::string>());
  }
  return static_cast<int>(value);
}

RobotOrder order_from_row(const double* row, const InProcessSim& sim, const std::string& where) {
  RobotOrder order;
  order.team = static_cast<Team>(whole_number(row[kTeam], 0, 1, where + "team (0 yellow, 1 blue)"));
  order.id = whole_number(row[kId], 0, 99, where + "id");
  robot_command_t& c = order.command;
  c.robot_id = order.id;
  c.mode = static_cast<std::int8_t>(whole_number(row[kMode], 0, 2, where + "mode"));
  c.vx = row[kVx];
  c.vy = row[kVy];
  c.omega = row[kOmega];
  c.kick_speed = row[kKickSpeed];
  c.chip_speed = row[kChipSpeed];
  c.chip_angle = row[kChipAngle];
  c.dribbler_speed = row[kDribblerSpeed];
  // Wheel speeds: as many as the robot has wheels; the columns past them must be 0.
  const std::size_t wheels = sim.wheel_count(order.team, order.id).value_or(kMaxWheels);
  for (std::size_t k = 0; k < static_cast<std::size_t>(kMaxWheels); ++k) {
    const double w = row[kWheel0 + k];
    if (k < wheels) {
      if (c.mode == robot_command_t::MODE_WHEEL_SPEEDS) c.wheel_speeds.push_back(w);
    } else if (w != 0) {
      throw py::value_error(where + "wheel" + std::to_string(k) +
                            " must be 0: " + robot_name(order.team, order.id) + " has " +
                            std::to_string(wheels) + " wheels");
    }
  }
  c.num_wheels = static_cast<std::int32_t>(c.wheel_speeds.size());
  return order;
}

}  // namespace

std::vector<RobotOrder> orders_from_array(const py::handle& commands, const InProcessSim& sim,
                                          const std::string& label) {
  std::vector<RobotOrder> orders;
  if (commands.is_none()) return orders;
  py::array_t<double, py::array::c_style | py::array::forcecast> array;
  try {
    array = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(commands);
  } catch (const py::error_already_set&) {
    array = {};
  }
  if (!array) throw py::type_error(label + "commands must be a numeric array of shape (n, 14)");
  const std::size_t columns = kCommandColumns.size();
  if (array.ndim() == 1 && array.shape(0) == 0) return orders;  // np.array([]): no commands
  if (array.ndim() != 2 || static_cast<std::size_t>(array.shape(1)) != columns) {
    std::string shape = "(";
    for (py::ssize_t d = 0; d < array.ndim(); ++d) {
      shape += (d ? ", " : "") + std::to_string(array.shape(d));
    }
    throw py::value_error(label + "commands must have shape (n, " + std::to_string(columns) +
                          ") (columns: ubersim.COMMAND_COLUMNS), got " + shape +
                          (array.ndim() == 1 ? ",)" : ")"));
  }
  const double* data = array.data();
  for (py::ssize_t row = 0; row < array.shape(0); ++row) {
    const std::string where = label + "commands row " + std::to_string(row) + ": ";
    orders.push_back(order_from_row(data + static_cast<std::size_t>(row) * columns, sim, where));
  }
  try {
    sim.check_orders(orders);
  } catch (const std::invalid_argument& error) {
    throw py::value_error(label + error.what());
  }
  return orders;
}

py::array_t<double> robots_array(const sim_state_t& state) {
  auto out = matrix(state.robots.size(), kRobotColumns.size());
  auto cell = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < state.robots.size(); ++i) {
    const robot_state_t& r = state.robots[i];
    const auto row = static_cast<py::ssize_t>(i);
    const double values[] = {static_cast<double>(r.team),
                             static_cast<double>(r.robot_id),
                             r.x,
                             r.y,
                             r.orientation,
                             r.vx,
                             r.vy,
                             r.omega,
                             r.ball_contact ? 1.0 : 0.0,
                             r.kicker_charged ? 1.0 : 0.0};
    py::ssize_t column = 0;
    for (double v : values) cell(row, column++) = v;
    for (int k = 0; k < kMaxWheels; ++k) {
      cell(row, column++) = k < r.num_wheels ? r.wheel_speeds[static_cast<std::size_t>(k)] : kNaN;
    }
  }
  return out;
}

py::array_t<double> ball_array(const sim_state_t& state) {
  py::array_t<double> out(static_cast<py::ssize_t>(kBallColumns.size()));
  auto cell = out.mutable_unchecked<1>();
  for (int k = 0; k < 3; ++k) {
    cell(k) = state.ball.position[k];
    cell(k + 3) = state.ball.linear_velocity[k];
  }
  return out;
}

py::array_t<double> detections_array(const std::vector<vision_frame_t>& frames) {
  std::size_t rows = 0;
  for (const auto& f : frames)
    rows += f.balls.size() + f.robots_yellow.size() + f.robots_blue.size();
  auto out = matrix(rows, kDetectionColumns.size());
  auto cell = out.mutable_unchecked<2>();
  py::ssize_t row = 0;
  auto put = [&](const vision_frame_t& f, double kind, double id, double confidence, double x,
                 double y, double orientation) {
    const double values[] = {static_cast<double>(f.camera_id),
                             static_cast<double>(f.frame_number),
                             f.t_capture,
                             f.t_sent,
                             kind,
                             id,
                             confidence,
                             x,
                             y,
                             orientation};
    py::ssize_t column = 0;
    for (double v : values) cell(row, column++) = v;
    ++row;
  };
  for (const auto& f : frames) {
    for (const auto& b : f.balls) put(f, kKindBall, -1, b.confidence, b.x, b.y, kNaN);
    for (const auto& r : f.robots_yellow) {
      put(f, kKindYellow, r.robot_id, r.confidence, r.x, r.y, r.orientation);
    }
    for (const auto& r : f.robots_blue) {
      put(f, kKindBlue, r.robot_id, r.confidence, r.x, r.y, r.orientation);
    }
  }
  return out;
}

py::array_t<double> frames_array(const std::vector<vision_frame_t>& frames) {
  auto out = matrix(frames.size(), kFrameColumns.size());
  auto cell = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const vision_frame_t& f = frames[i];
    const double values[] = {static_cast<double>(f.camera_id),
                             static_cast<double>(f.frame_number),
                             f.t_capture,
                             f.t_sent,
                             static_cast<double>(f.balls.size()),
                             static_cast<double>(f.robots_yellow.size()),
                             static_cast<double>(f.robots_blue.size())};
    py::ssize_t column = 0;
    for (double v : values) cell(static_cast<py::ssize_t>(i), column++) = v;
  }
  return out;
}

py::array_t<double> feedback_array(const std::vector<std::pair<Team, radio_feedback_t>>& feedback) {
  std::size_t rows = 0;
  for (const auto& [team, packet] : feedback) rows += packet.robots.size();
  auto out = matrix(rows, kFeedbackColumns.size());
  auto cell = out.mutable_unchecked<2>();
  py::ssize_t row = 0;
  for (const auto& [team, packet] : feedback) {
    for (const auto& r : packet.robots) {
      const double values[] = {static_cast<double>(team),  static_cast<double>(r.robot_id),
                               packet.t_measured,          packet.t_sent,
                               r.ball_contact ? 1.0 : 0.0, r.kicker_charged ? 1.0 : 0.0};
      py::ssize_t column = 0;
      for (double v : values) cell(row, column++) = v;
      ++row;
    }
  }
  return out;
}

py::dict truth_dict(const sim_state_t& state) {
  py::dict out;
  out["time"] = state.sim_time;
  out["robots"] = robots_array(state);
  out["ball"] = ball_array(state);
  return out;
}

py::dict step_dict(const StepOutput& step) {
  py::dict out = truth_dict(step.truth);
  out["vision"] = detections_array(step.frames);
  out["frames"] = frames_array(step.frames);
  out["feedback"] = feedback_array(step.feedback);
  return out;
}

}  // namespace ubersim::python
