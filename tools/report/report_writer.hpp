#pragma once
// Writes what the experiments measured: data files for gnuplot (whitespace
// separated, one header line starting with '#', trials as gnuplot data
// blocks) and the markdown sections of the report, with every target beside
// its figure. Deciding (decide_fidelity: which target is met) is apart from
// writing (write_fidelity_markdown: how the report shows it).
#include <optional>
#include <string>
#include <vector>

#include "acceleration.hpp"
#include "ball.hpp"
#include "figure8.hpp"
#include "targets.hpp"

namespace ubersim::report {

struct FidelityResults {
  std::vector<RampResult> ramps;
  std::vector<SweepResult> sweeps;
  std::vector<Figure8Result> figure8;
  std::vector<BallResult> ball;  // zero or one
};

// Data files (see the gnuplot scripts in tools/report/plots/) and values.gp
// (predictions as gnuplot variables).
void write_data_files(const std::string& dir, const FidelityResults& results);

// Checks shown together as one figure of the report.
struct CheckGroup {
  std::vector<Check> checks;
  std::optional<Check> worst;  // a missed one if any, the largest error among those
  int missed = 0;
  bool met() const { return missed == 0; }
};

// One robot type's acceleration ramp (check_ramp), as its table rows show it.
struct RampVerdict {
  std::vector<Check> checks;  // every check of the ramp, in check_ramp's order
  CheckGroup acceleration;    // ground truth and VISION
  CheckGroup top_speed;
};

// One robot type's saturation sweep (check_sweep).
struct SweepVerdict {
  std::vector<Check> checks;  // in check_sweep's order, the saturation last
  Check saturation;
  CheckGroup below_saturation;  // the ramps slower than the predicted saturation
};

// A flat kick or a chip against its model: relative errors of its two figures.
struct PairVerdict {
  double first_error = 0;   // roll-out distance, or chip flight distance
  double second_error = 0;  // roll-out time, or chip peak height
  bool met = false;         // both within the tolerance
};

struct BallVerdict {
  std::vector<Check> checks;  // check_ball's
  std::vector<PairVerdict> kicks;
  std::vector<PairVerdict> chips;
};

// A row of the targets table: one target over a group of checks.
struct TargetRow {
  std::string target;
  CheckGroup group;
};

// Everything the fidelity report decides, one entry per result of
// FidelityResults in the same order; nothing here is text of the report.
struct FidelityVerdicts {
  std::vector<RampVerdict> ramps;
  std::vector<SweepVerdict> sweeps;
  std::vector<BallVerdict> ball;
  std::vector<TargetRow> targets;  // rows with no checks are left out of the table
  std::vector<Check> all;          // every check: ramps, sweeps, ball
  int missed = 0;                  // of all
};

// Judges every result against the tolerances.
FidelityVerdicts decide_fidelity(const FidelityResults& results, const Tolerances& tolerances = {});

// fidelity.md (sections 1-3 of the report) and targets_fidelity.md (rows of
// the summary table), from the results and what was decided on them.
void write_fidelity_markdown(const std::string& dir, const FidelityResults& results,
                             const FidelityVerdicts& verdicts, const ExperimentSetup& setup);

}  // namespace ubersim::report
