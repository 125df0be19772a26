#pragma once
// Writes what the experiments measured: data files for gnuplot (whitespace
// separated, one header line starting with '#', trials as gnuplot data
// blocks) and the markdown sections of the report, with every target beside
// its figure.
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

// fidelity.md (sections 1-3 of the report) and targets_fidelity.md (rows of
// the summary table). Returns the number of targets missed.
int write_fidelity_markdown(const std::string& dir, const FidelityResults& results,
                            const ExperimentSetup& setup);

}  // namespace ubersim::report
