// ubersim_referee: sets up the field and controls the simulation over
// SIM_CONTROL, reporting what the physics server answered. Exit status:
// 0 done, 1 physics refused (its message is printed), 2 no answer / bad usage.
#include <CLI/CLI.hpp>
#include <cmath>
#include <iostream>
#include <map>
#include <optional>
#include <ubersim/team_t.hpp>

#include "ubersim/angles.hpp"
#include "ubersim/cli.hpp"
#include "ubersim/config.hpp"
#include "ubersim/field_side.hpp"
#include "ubersim/logging.hpp"
#include "ubersim/process_main.hpp"
#include "ubersim/referee/autoref_shell.hpp"
#include "ubersim/referee/robot_radii.hpp"
#include "ubersim/referee/scene_io.hpp"
#include "ubersim/referee/sim_link.hpp"
#include "ubersim/referee/situations.hpp"
#include "ubersim/scenario_config.hpp"

namespace {

using namespace ubersim;
using namespace ubersim::referee;
using std::chrono::milliseconds;

int8_t wire_team(Team team) {
  return team == Team::Blue ? team_t::BLUE : team_t::YELLOW;
}

struct Options {
  CommonOptions common;
  double timeout_s = 2.0;
  std::string yellow_defends = "negative";
  // Arguments of the subcommands.
  std::string team_text;
  int robot_id = 0;
  std::string robot_type;
  double x = 0, y = 0, z = 0, heading_deg = 0;
  std::vector<double> velocity;
  int steps = 1;
  std::string speed = "1";  // a factor, or "sync"
  std::int64_t seed = 0;
  std::string dribbling;  // "perfect" or "simulated"
  std::string scenario;
  // auto
  std::string game = "division_b";
  double game_length = 0;
  std::optional<std::string> yellow_name, blue_name;  // override YELLOW_NAME / BLUE_NAME
  std::string events_file;
  bool keep_running = false;
  bool repeat = false;
  double team_wait = 10;
  bool start_physics = false;
  bool sync = false;
  bool judge_every_step = false;
};

// `auto`: the automatic referee runs the game until it is over.
int run_auto(const Options& o) {
  AutoOptions a;
  a.common = o.common;
  a.game = load_game_config(o.common.config_root(), o.game);
  if (o.game_length > 0) a.game.game_length = o.game_length;
  if (o.yellow_name) a.game.yellow_name = *o.yellow_name;
  if (o.blue_name) a.game.blue_name = *o.blue_name;
  a.sides.yellow_defends = ubersim::parse_defended_side(o.yellow_defends);
  a.events_file = o.events_file;
  a.timeout_s = o.timeout_s;
  a.exit_at_end = !o.keep_running;
  a.repeat = o.repeat;
  // In sync mode physics starts only once every team's program is there (the sync gate).
  a.game.team_wait = o.sync ? 0 : o.team_wait;
  a.start_physics = o.start_physics;
  a.sync = o.sync;
  a.judge_every_step = o.judge_every_step;
  return run_auto_referee(a);
}

class Referee {
 public:
  explicit Referee(const Options& options)
      : options_(options),
        bus_(with_receive_buffer(options.common.lcm_url)),
        link_(bus_, options.common.channels(), "ubersim_referee") {}

  milliseconds timeout() const {
    return milliseconds(static_cast<long>(options_.timeout_s * 1000));
  }

  Team team() const {
    Team team{};
    if (!parse_team(options_.team_text, team)) {
      throw CLI::ValidationError("team",
                                 "expected yellow or blue, got '" + options_.team_text + "'");
    }
    return team;
  }

  double radius_of(const std::string& type) { return radii_(type); }

  int send(sim_control_t control, milliseconds extra = milliseconds(0)) {
    const auto ack = link_.request(std::move(control), timeout() + extra);
    if (!ack.ok) {
      std::cerr << "physics refused: " << ack.message << "\n";
      return 1;
    }
    std::cout << "ok (sim time " << ack.sim_time << " s, step " << ack.step << "): " << ack.message
              << "\n";
    return 0;
  }

  int simple(int8_t action) {
    sim_control_t control{};
    control.action = action;
    return send(control);
  }

  int step() {
    sim_control_t control{};
    control.action = sim_control_t::STEP;
    control.step_count = options_.steps;
    // Stepping takes time: allow 10 ms of wall time per step on top.
    return send(control, milliseconds(10L * options_.steps));
  }

  int speed() {
    sim_control_t control{};
    if (options_.speed == "sync") {
      // Sync mode needs the radio emulator's horizon (ubersim_radio --sync): docs/sync.md.
      control.action = sim_control_t::SET_SYNC;
      return send(control);
    }
    control.action = sim_control_t::SET_SPEED;
    try {
      std::size_t used = 0;
      control.speed_factor = std::stod(options_.speed, &used);
      if (used != options_.speed.size()) throw std::invalid_argument(options_.speed);
    } catch (const std::exception&) {
      std::cerr << "speed: expected a number or 'sync', got '" << options_.speed << "'\n";
      return 2;
    }
    return send(control);
  }

  int seed() {
    sim_control_t control{};
    control.action = sim_control_t::SET_SEED;
    control.seed = options_.seed;
    return send(control);
  }

  // Physics' dribbler mode for every robot (SET_DRIBBLING).
  int dribbling() {
    sim_control_t control{};
    control.action = sim_control_t::SET_DRIBBLING;
    control.perfect_dribbling = options_.dribbling == "perfect";
    return send(control);
  }

  int geometry() {
    const auto g = link_.geometry(timeout());
    std::cout << "field " << g.name << ": " << g.field_length << " x " << g.field_width
              << " m, boundary " << g.boundary_width << " m (behind the goal lines "
              << g.boundary_width_goal_line << " m), goals " << g.goal_width
              << " m wide, penalty mark " << g.penalty_mark_distance
              << " m from the goal attacked, ball radius " << g.ball_radius << " m\n";
    return 0;
  }

  int state() {
    const auto s = link_.state(timeout());
    std::cout << "sim time " << s.sim_time << " s, step " << s.step << (s.paused ? ", paused" : "")
              << "\nball " << s.ball.position[0] << " " << s.ball.position[1] << " "
              << s.ball.position[2] << "\n";
    for (const auto& r : s.robots) {
      std::cout << (r.team == team_t::BLUE ? "blue " : "yellow ") << r.robot_id << " "
                << r.robot_type << " " << r.x << " " << r.y << " " << r.orientation / kDegToRad
                << " deg\n";
    }
    return 0;
  }

  // Adds or moves one robot; robots in its way are moved aside and stopped.
  int place_robot(bool add) {
    const auto state = link_.state(timeout());
    const auto field = link_.geometry(timeout());
    const auto before = scene_from_state(state, field.ball_radius,
                                         [this](const std::string& t) { return radius_of(t); });
    PlacementScene planned = before;
    const Team which = team();
    auto found = std::find_if(planned.robots.begin(), planned.robots.end(), [&](const auto& r) {
      return r.team == which && r.id == options_.robot_id;
    });
    if (found == planned.robots.end()) {
      if (!add) {
        std::cerr << "no " << team_name(which) << " robot " << options_.robot_id
                  << " on the field (use 'add' to put one there)\n";
        return 1;
      }
      planned.robots.push_back(PlacedRobot{});
      found = planned.robots.end() - 1;
    }
    found->team = which;
    found->id = options_.robot_id;
    if (add) found->radius = radius_of(options_.robot_type);
    found->x = options_.x;
    found->y = options_.y;
    found->orientation = options_.heading_deg * kDegToRad;
    found->fixed = true;
    const std::size_t index = static_cast<std::size_t>(found - planned.robots.begin());
    if (!separate(planned, bounds_of(field))) {
      std::cerr << "cannot place it there without overlapping something\n";
      return 1;
    }
    auto control = place_request(before, planned, false, false);
    // The robot asked for always goes (place_request skips robots that did not move).
    auto placed = std::find_if(control.robots.begin(), control.robots.end(), [&](const auto& p) {
      return p.team == wire_team(which) && p.robot_id == options_.robot_id;
    });
    if (placed == control.robots.end()) {
      control.robots.push_back(to_placement(planned.robots[index]));
      control.num_robots = static_cast<int32_t>(control.robots.size());
      placed = control.robots.end() - 1;
    }
    if (add) placed->robot_type = options_.robot_type;
    if (options_.velocity.size() == 3) {
      placed->vx = options_.velocity[0];
      placed->vy = options_.velocity[1];
      placed->omega = options_.velocity[2];
    }
    return send(control);
  }

  int remove_robot() {
    sim_control_t control{};
    control.action = sim_control_t::PLACE;
    robot_placement_t p{};
    p.team = wire_team(team());
    p.robot_id = options_.robot_id;
    p.present = false;
    control.robots.push_back(p);
    control.num_robots = 1;
    return send(control);
  }

  int place_ball() {
    const auto state = link_.state(timeout());
    const auto field = link_.geometry(timeout());
    const auto before = scene_from_state(state, field.ball_radius,
                                         [this](const std::string& t) { return radius_of(t); });
    PlacementScene planned = before;
    planned.ball_x = options_.x;
    planned.ball_y = options_.y;
    if (options_.z <= field.ball_radius && !separate(planned, bounds_of(field))) {
      std::cerr << "cannot place the ball there without overlapping a robot\n";
      return 1;
    }
    auto control = place_request(before, planned, true, false);
    control.ball.position[2] = options_.z;
    for (std::size_t i = 0; i < options_.velocity.size() && i < 3; ++i) {
      control.ball.linear_velocity[i] = options_.velocity[i];
    }
    return send(control);
  }

  int setup() {
    const auto scenario = load_scenario_config(options_.common.config_root(), options_.scenario);
    const auto field = link_.geometry(timeout());
    if (field.name != scenario.field) {
      std::cerr << "note: scenario " << scenario.name << " is made for field " << scenario.field
                << "; physics runs " << field.name << " (robots are placed as the file says)\n";
    }
    sim_control_t control{};
    control.action = sim_control_t::SETUP;
    for (const auto& r : scenario.robots) {
      robot_placement_t p{};
      p.team = wire_team(r.team);
      p.robot_id = r.id;
      p.robot_type = r.type;
      p.present = true;
      p.x = r.x;
      p.y = r.y;
      p.orientation = r.orientation;
      control.robots.push_back(p);
    }
    control.num_robots = static_cast<int32_t>(control.robots.size());
    control.has_ball = true;
    control.ball.position[0] = scenario.ball_x;
    control.ball.position[1] = scenario.ball_y;
    return send(control);
  }

  int situation(Situation kind) {
    const auto state = link_.state(timeout());
    const auto field = link_.geometry(timeout());
    const auto before = scene_from_state(state, field.ball_radius,
                                         [this](const std::string& t) { return radius_of(t); });
    SituationRequest request;
    request.kind = kind;
    if (kind == Situation::KickOff || kind == Situation::FreeKick || kind == Situation::Penalty) {
      request.team = team();
    }
    request.x = options_.x;
    request.y = options_.y;
    FieldSides sides;
    sides.yellow_defends = ubersim::parse_defended_side(options_.yellow_defends);
    const auto planned = plan_situation(request, before, field, sides);
    // Every robot is stopped in a set piece; the ball too.
    return send(place_request(before, planned, true, true));
  }

 private:
  const Options& options_;
  MessageBus bus_;
  SimLink link_;
  RobotRadii radii_{options_.common.config_root()};
};

using Action = std::function<int(Referee&)>;
using Actions = std::map<std::string, Action>;  // by subcommand name

CLI::App* add_command(CLI::App& app, Actions& actions, const std::string& name,
                      const std::string& help, Action action) {
  actions[name] = std::move(action);
  return app.add_subcommand(name, help);
}

void add_team_arg(CLI::App* command, Options& o) {
  command->add_option("team", o.team_text, "yellow | blue")->required();
}

void add_xy_args(CLI::App* command, Options& o) {
  command->add_option("x", o.x, "m")->required();
  command->add_option("y", o.y, "m")->required();
}

void add_global_options(CLI::App& app, Options& o) {
  add_common_options(app, o.common);
  app.add_option("--timeout", o.timeout_s, "seconds to wait for the physics server")
      ->capture_default_str()
      ->check(ubersim::greater_than(0));
  app.add_option("--yellow-defends", o.yellow_defends, "which goal yellow defends")
      ->check(CLI::IsMember(ubersim::kDefendedSides))
      ->capture_default_str();
}

// Subcommands that control the simulation or ask it something.
void add_control_commands(CLI::App& app, Options& o, Actions& actions) {
  add_command(app, actions, "ping", "check that the physics server answers",
              [](Referee& r) { return r.simple(sim_control_t::PING); });
  add_command(app, actions, "pause", "pause the simulation",
              [](Referee& r) { return r.simple(sim_control_t::PAUSE); });
  add_command(app, actions, "resume", "resume the simulation",
              [](Referee& r) { return r.simple(sim_control_t::RESUME); });
  add_command(app, actions, "reset", "reset to the scenario physics started with",
              [](Referee& r) { return r.simple(sim_control_t::RESET); });
  add_command(app, actions, "step", "advance N physics steps (paused or lockstep)",
              [](Referee& r) { return r.step(); })
      ->add_option("n", o.steps, "steps")
      ->required()
      ->check(ubersim::greater_than(0));
  add_command(app, actions, "speed",
              "set the speed: 1 real time, 0.5, 4 ..., 0 as fast as possible, -1 lockstep, sync "
              "(docs/sync.md)",
              [](Referee& r) { return r.speed(); })
      ->add_option("factor", o.speed)
      ->required();
  add_command(app, actions, "seed", "set the random seed", [](Referee& r) { return r.seed(); })
      ->add_option("seed", o.seed)
      ->required();
  add_command(app, actions, "dribbling",
              "perfect: a dribbler that is on holds the ball it touches rigidly (ER-Force's "
              "simulate_dribbling = false); simulated: the roller's contact only (the default)",
              [](Referee& r) { return r.dribbling(); })
      ->add_option("mode", o.dribbling)
      ->required()
      ->check(CLI::IsMember({"perfect", "simulated"}));
  add_command(app, actions, "geometry", "print the field geometry",
              [](Referee& r) { return r.geometry(); });
  add_command(app, actions, "state", "print where everything is",
              [](Referee& r) { return r.state(); });
}

// Subcommands that put robots and the ball somewhere.
void add_placement_commands(CLI::App& app, Options& o, Actions& actions) {
  auto* add = add_command(app, actions, "add", "put a robot on the field",
                          [](Referee& r) { return r.place_robot(true); });
  add_team_arg(add, o);
  add->add_option("id", o.robot_id)->required();
  add->add_option("type", o.robot_type, "robot config name")->required();
  add_xy_args(add, o);
  add->add_option("heading", o.heading_deg, "deg");

  auto* remove = add_command(app, actions, "remove", "take a robot off the field",
                             [](Referee& r) { return r.remove_robot(); });
  add_team_arg(remove, o);
  remove->add_option("id", o.robot_id)->required();

  auto* place = add_command(app, actions, "place-robot",
                            "move a robot (robots in the way move aside and stop)",
                            [](Referee& r) { return r.place_robot(false); });
  add_team_arg(place, o);
  place->add_option("id", o.robot_id)->required();
  add_xy_args(place, o);
  place->add_option("heading", o.heading_deg, "deg");
  place->add_option("--velocity", o.velocity, "vx vy omega (m/s, m/s, rad/s, field frame)")
      ->expected(3);

  auto* ball = add_command(app, actions, "place-ball",
                           "move the ball (robots in the way move aside and stop)",
                           [](Referee& r) { return r.place_ball(); });
  add_xy_args(ball, o);
  ball->add_option("--z", o.z, "height (m)");
  ball->add_option("--velocity", o.velocity, "vx vy [vz] (m/s)")->expected(2, 3);

  add_command(app, actions, "setup", "put robots and ball where a scenario file says",
              [](Referee& r) { return r.setup(); })
      ->add_option("scenario", o.scenario, "scenario name or path")
      ->required();
}

// Subcommands that set up a game situation by the SSL rules.
void add_situation_commands(CLI::App& app, Options& o, Actions& actions) {
  add_team_arg(add_command(app, actions, "kickoff", "kick-off for a team",
                           [](Referee& r) { return r.situation(Situation::KickOff); }),
               o);
  auto* free_kick = add_command(app, actions, "free-kick", "free kick for a team at x y",
                                [](Referee& r) { return r.situation(Situation::FreeKick); });
  add_team_arg(free_kick, o);
  add_xy_args(free_kick, o);
  add_team_arg(add_command(app, actions, "penalty", "penalty kick for a team",
                           [](Referee& r) { return r.situation(Situation::Penalty); }),
               o);
  add_xy_args(
      add_command(app, actions, "ball-placement", "place the ball at x y, robots keep 0.5 m away",
                  [](Referee& r) { return r.situation(Situation::BallPlacement); }),
      o);
  add_command(app, actions, "stop", "stop: every robot 0.5 m from the ball and still",
              [](Referee& r) { return r.situation(Situation::Stop); });
}

// `auto`: runs on its own (run_auto), not through a Referee.
void add_auto_command(CLI::App& app, Options& o) {
  auto* automatic = app.add_subcommand(
      "auto",
      "automatic referee: run the game (kick-offs, goals, outs, fouls, halves) until it ends");
  automatic->add_option("--game", o.game, "game config (config/referee/<name>.cfg)")
      ->capture_default_str();
  automatic->add_option("--game-length", o.game_length, "s of sim time (overrides GAME_LENGTH)")
      ->check(ubersim::greater_than(0));
  const CLI::Validator team_name(
      [](const std::string& name) { return ubersim::referee::team_name_problem(name); }, "NAME");
  automatic
      ->add_option("--yellow-name", o.yellow_name,
                   "the yellow team's name on REFEREE (overrides YELLOW_NAME; default Yellow)")
      ->check(team_name);
  automatic
      ->add_option("--blue-name", o.blue_name,
                   "the blue team's name on REFEREE (overrides BLUE_NAME; default Blue)")
      ->check(team_name);
  automatic->add_option("--events", o.events_file, "write the event log (JSON lines) here");
  automatic->add_flag("--keep-running", o.keep_running, "do not exit when the game is over");
  automatic->add_flag("--start", o.start_physics,
                      "resume physics once listening (start physics with --paused)");
  auto* sync =
      automatic->add_flag("--sync", o.sync,
                          "REFEREE after every state: a physics started with --sync-referee waits "
                          "for it, placements apply at a fixed step, games are reproducible");
  automatic
      ->add_flag("--repeat", o.repeat,
                 "when a game is over, start a new one 5 s of sim time later, until stopped")
      ->excludes(sync);
  automatic
      ->add_option("--team-wait", o.team_wait,
                   "s of sim time the game stays in HALT before its first STOP until every team "
                   "on the field has sent a command (an SSL AI leaves its halt on STOP); 0: "
                   "start at once; not in sync mode")
      ->capture_default_str()
      ->check(ubersim::in_range(0.0, 3600.0));
  automatic->add_flag("--judge-every-step", o.judge_every_step,
                      "judge every state (default: only the states where a rule could decide, "
                      "docs/autoref.md; the same decisions at a fraction of the cost)");
}

// Runs the subcommand the command line named; its exit status.
int run_subcommand(const CLI::App& app, const Options& o, const Actions& actions) {
  const bool is_auto = app.got_subcommand("auto");
  // Quiet by default as a command-line tool; the automatic referee logs its game.
  setup_logging("referee", o.common.verbosity() - (is_auto ? 0 : 1));
  try {
    if (is_auto) return run_auto(o);
    Referee referee(o);
    return actions.at(app.get_subcommands().front()->get_name())(referee);
  } catch (const NoAnswer& error) {
    std::cerr << "referee: " << error.what() << "\n";
    return 2;
  } catch (const CLI::ValidationError& error) {
    std::cerr << "referee: " << error.what() << "\n";
    return 2;
  }
}

int parse_and_run(int argc, char** argv) {
  Options o;
  Actions actions;
  CLI::App app{"ubersim referee: set up the field and control the simulation"};
  app.require_subcommand(1);
  add_global_options(app, o);
  add_control_commands(app, o, actions);
  add_placement_commands(app, o, actions);
  add_situation_commands(app, o, actions);
  add_auto_command(app, o);
  if (const auto stop = ubersim::parse_command_line(app, argc, argv)) return *stop;
  return run_subcommand(app, o, actions);
}

}  // namespace

int main(int argc, char** argv) {
  return ubersim::run_main("referee", [&] { return parse_and_run(argc, argv); });
}
