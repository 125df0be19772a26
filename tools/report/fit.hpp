#pragma once
// Least-squares fits and error summaries used by every experiment.
#include <cstddef>
#include <vector>

namespace ubersim::report {

struct LineFit {
  double slope = 0;      // dy/dx
  double intercept = 0;  // y at x = 0
  double slope_standard_error = 0;
  std::size_t points = 0;
};
// y = intercept + slope x. Fewer than 3 points or all x equal: points = 0.
LineFit fit_line(const std::vector<double>& x, const std::vector<double>& y);

struct QuadraticFit {
  double c0 = 0, c1 = 0, c2 = 0;  // y = c0 + c1 x + c2 x^2
  double c2_standard_error = 0;   // from the residuals
  std::size_t points = 0;
};
// Centred on the mean of x for conditioning. Fewer than 5 points: points = 0.
QuadraticFit fit_quadratic(const std::vector<double>& x, const std::vector<double>& y);

struct ErrorSummary {
  double rms = 0;
  double max = 0;
  double mean = 0;
  std::size_t count = 0;
};
ErrorSummary summarise(const std::vector<double>& errors);

double mean(const std::vector<double>& values);
double standard_deviation(const std::vector<double>& values);  // sample (n - 1)

}  // namespace ubersim::report
