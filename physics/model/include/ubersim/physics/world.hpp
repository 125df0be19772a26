#pragma once
// The simulated world: field, ball and robots in one ODE world, stepped at a
// fixed rate. Usable in-process (tests, benchmarks) and by the server, which
// adds messages and pacing around it. Stepping is deterministic: the same
// setup, seed and command stream give bit-identical states.
#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <ubersim/field_geometry_t.hpp>
#include <ubersim/sim_commands_t.hpp>
#include <ubersim/sim_control_t.hpp>
#include <ubersim/sim_state_t.hpp>
#include <vector>

#include "ubersim/delay_line.hpp"
#include "ubersim/field_config.hpp"
#include "ubersim/logging.hpp"
#include "ubersim/physics/ball.hpp"
#include "ubersim/physics/contact_handler.hpp"
#include "ubersim/physics/field_builder.hpp"
#include "ubersim/physics/physics_config.hpp"
#include "ubersim/physics/robot.hpp"

namespace ubersim::physics {

struct RobotSpawn {
  Team team = Team::Yellow;
  int id = 0;
  std::string type;  // robot config name
  PlanarState state;
};

// Robot types by config name (loaded once, shared by every robot of the type).
using RobotTypeSource = std::function<std::shared_ptr<const RobotTypeConfig>(const std::string&)>;
// Loads config/robots/<name>.cfg from `config_dir`, caching; throws ConfigError.
RobotTypeSource robot_types_from(const std::string& config_dir);

struct WorldSetup {
  FieldConfig field;
  BallConfig ball;
  PhysicsConfig physics;
  double ball_x = 0, ball_y = 0;  // m
  std::vector<RobotSpawn> robots;
  RobotTypeSource robot_types;
  std::uint64_t seed = 0;
};

// A scenario's world. Throws ConfigError.
WorldSetup load_world_setup(const std::string& config_dir, const std::string& scenario,
                            const std::string& physics_config);

// The setup's robots and ball moved onto another field: their positions are
// scaled by the ratio of the field sizes (a Division B line-up stays a line-up
// on a 6 x 4 m field), and the field replaced.
void put_on_field(WorldSetup& setup, const FieldConfig& field);

struct WorldCounters {
  std::uint64_t commands_applied = 0;
  std::uint64_t commands_dropped = 0;  // non-finite, bad mode, bad wheel count
  ClampCounts commands_clamped;        // applied at the robot type's limits
  std::uint64_t commands_unknown_robot = 0;
  std::uint64_t packets_dropped = 0;  // bad team or time
  std::uint64_t bodies_reset = 0;     // non-finite or outside the walls
  std::uint64_t robots_set_upright = 0;
  std::uint64_t kicks = 0;
};

// The commands line of the terminal summary at stop and of the PING answer
// (`ubersim_referee ping`): "commands: 1200 applied, 3 at a robot type's limit (kick speed 3),
// ...".
std::string command_summary(const WorldCounters& counters);

struct PlaceOutcome {
  bool ok = false;
  std::string message;
};

class World {
 public:
  explicit World(WorldSetup setup);
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  // One fixed step of dt.
  void step();
  // Back to the setup: sim time 0, step 0, the setup's robots and ball.
  void reset();
  // Seed of ODE's solver randomness (constraint ordering); kept over resets.
  void set_seed(std::uint64_t seed);

  double time() const { return static_cast<double>(step_) * dt_; }
  std::int64_t step_index() const { return step_; }
  double dt() const { return dt_; }

  // A packet from the radio emulator: held until the first step whose sim
  // time is >= t_apply, then each robot named in it takes its command.
  void submit(const sim_commands_t& packet);
  // Applies one command now (in-process users; same checks as submit).
  void command(Team team, int id, const robot_command_t& command, double timeout = 0);

  // PLACE (and SETUP, which first removes every robot).
  PlaceOutcome place(const sim_control_t& request, bool remove_all_first);
  Robot& add_robot(Team team, int id, const std::string& type, const PlanarState& state);
  // A robot type defined at run time (SIM_CONTROL DEFINE_ROBOT_TYPE): found by
  // its name before the config files from then on, also after a reset. A robot
  // takes it when placed with that name. Throws ConfigError (file = the type's
  // name) for a bad text or when too many types are defined.
  void define_robot_type(const std::string& name, const std::string& config_text);
  // A field changed at run time (SIM_CONTROL SET_FIELD): the keys of
  // field_text replace those of the field in use, the static field is
  // rebuilt, bodies outside the new walls are moved in. Also kept over RESET.
  // BALL_RADIUS in the text gives the ball another radius (change_ball_radius).
  // Throws ConfigError (std::invalid_argument when a robot type cannot reach
  // such a ball); nothing changes then. Returns what was done.
  std::string change_field(const std::string& field_text);
  // The ball in play gets `radius` where it is (same mass and surface), and
  // every robot is rebuilt where it stands around it (the dribbler's roller
  // and the kicker reach follow the ball). Kept over RESET.
  void change_ball_radius(double radius);
  bool remove_robot(Team team, int id);
  Robot* robot(Team team, int id);
  // SIM_CONTROL SET_DRIBBLING: true = a dribbler that is on holds the ball it
  // touches rigidly (Robot::update_hold), false = the roller's contact only.
  // Kept over reset().
  void set_perfect_dribbling(bool perfect);
  bool perfect_dribbling() const { return perfect_dribbling_; }
  // Ball at a position (z = 0: resting on the floor) with a velocity, no spin.
  void place_ball(double x, double y, double z, double vx, double vy, double vz);

  Ball& ball() { return *ball_; }
  const Ball& ball() const { return *ball_; }
  const std::vector<std::unique_ptr<Robot>>& robots() const { return robots_; }
  const WorldSetup& setup() const { return setup_; }
  const WorldCounters& counters() const { return counters_; }
  dWorldID ode_world() const { return world_.get(); }

  // Fills time, step, dt, ball and robots (the server adds paused and speed).
  void fill_state(sim_state_t& out) const;
  field_geometry_t geometry() const { return setup_.field.to_message(setup_.ball.radius); }

 private:
  void build();
  void apply_due_commands();
  void apply_command(Team team, int id, const robot_command_t& raw, double timeout);
  // Resets broken bodies (non-finite, beyond the speed caps, outside the
  // walls); after a step also sets tipped robots upright and notes good poses.
  void check_safety(bool after_step);
  bool body_sane(dBodyID body) const;
  bool inside_walls(double x, double y, double margin) const;
  void move_ball_out_of_robots(std::string& notes);
  // PLACE in parts. The checks return what is wrong (empty: nothing) and pick
  // each named robot type; applying changes the world.
  std::string check_placement(const sim_control_t& request, bool remove_all_first,
                              std::vector<std::shared_ptr<const RobotTypeConfig>>& types);
  std::string check_robot_placement(const robot_placement_t& p, bool remove_all_first,
                                    std::shared_ptr<const RobotTypeConfig>& type);
  // One present robot (`type` null: it keeps its own); true when it was placed.
  bool apply_robot_placement(const robot_placement_t& p,
                             std::shared_ptr<const RobotTypeConfig> type, std::string& notes);
  void apply_ball_placement(const sim_control_t& request, std::string& notes);
  // Moves by force (placement mode BY_FORCE), applied every step until ended.
  void apply_force_moves();

  WorldSetup setup_;
  // Types defined at run time, consulted by setup_.robot_types before the files.
  std::shared_ptr<std::map<std::string, std::shared_ptr<const RobotTypeConfig>>> defined_types_;
  double dt_;
  BallSurface ball_surface_;
  // The world's own threading implementation (self-threaded: each step's
  // jobs run on the calling thread). Without one ODE uses a process-wide
  // default, which worlds stepped at the same time on several threads (the
  // Python VectorSim) corrupt. Declared first: it outlives the world.
  ThreadingHandle threading_;
  // ODE objects in creation order: destroyed in reverse, the world last.
  WorldHandle world_;
  SpaceHandle space_;
  JointGroupHandle contacts_;
  std::unique_ptr<StaticField> field_;
  std::unique_ptr<Ball> ball_;
  std::vector<std::unique_ptr<Robot>> robots_;  // sorted by team, then id
  std::unique_ptr<ContactHandler> contact_handler_;

  std::int64_t step_ = 0;
  bool perfect_dribbling_ = false;
  unsigned long solver_random_state_ = 0;
  std::array<DelayLine<sim_commands_t>, 2> pending_;  // per team: each keeps its own order
  std::array<double, 3> ball_last_good_{};
  WorldCounters counters_;
  ThrottledLog log_;
  std::vector<dBodyID> body_buffer_;
  std::vector<char> kicked_buffer_;
  struct ForceTarget {
    double x = 0, y = 0, orientation = 0;  // m, m, rad
  };
  std::optional<ForceTarget> ball_force_;
  std::map<std::pair<int, int>, ForceTarget> robot_force_;  // (team, id)
};

}  // namespace ubersim::physics
