#include "fit.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace ubersim::report {

LineFit fit_line(const std::vector<double>& x, const std::vector<double>& y) {
  LineFit fit;
  const std::size_t n = std::min(x.size(), y.size());
  if (n < 3) return fit;
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < n; ++i) {
    mx += x[i];
    my += y[i];
  }
  mx /= static_cast<double>(n);
  my /= static_cast<double>(n);
  double sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < n; ++i) {
    sxx += (x[i] - mx) * (x[i] - mx);
    sxy += (x[i] - mx) * (y[i] - my);
  }
  if (sxx <= 0) return fit;
  fit.slope = sxy / sxx;
  fit.intercept = my - fit.slope * mx;
  double residual = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double r = y[i] - fit.intercept - fit.slope * x[i];
    residual += r * r;
  }
  fit.slope_standard_error = std::sqrt(residual / static_cast<double>(n - 2) / sxx);
  fit.points = n;
  return fit;
}

QuadraticFit fit_quadratic(const std::vector<double>& x, const std::vector<double>& y) {
  QuadraticFit fit;
  const std::size_t n = std::min(x.size(), y.size());
  if (n < 5) return fit;
  double centre = 0;
  for (std::size_t i = 0; i < n; ++i) centre += x[i];
  centre /= static_cast<double>(n);
  Eigen::MatrixXd a(static_cast<Eigen::Index>(n), 3);
  Eigen::VectorXd b(static_cast<Eigen::Index>(n));
  for (std::size_t i = 0; i < n; ++i) {
    const double u = x[i] - centre;
    const auto row = static_cast<Eigen::Index>(i);
    a(row, 0) = 1;
    a(row, 1) = u;
    a(row, 2) = u * u;
    b(row) = y[i];
  }
  const Eigen::Vector3d c = a.colPivHouseholderQr().solve(b);
  const double residual = (a * c - b).squaredNorm();
  const Eigen::Matrix3d covariance =
      (a.transpose() * a).inverse() * (residual / static_cast<double>(n - 3));
  fit.c2_standard_error = std::sqrt(std::max(0.0, covariance(2, 2)));
  // Back from u = x - centre to x.
  fit.c2 = c(2);
  fit.c1 = c(1) - 2 * c(2) * centre;
  fit.c0 = c(0) - c(1) * centre + c(2) * centre * centre;
  fit.points = n;
  return fit;
}

ErrorSummary summarise(const std::vector<double>& errors) {
  ErrorSummary s;
  s.count = errors.size();
  if (errors.empty()) return s;
  double squares = 0, sum = 0;
  for (double e : errors) {
    squares += e * e;
    sum += e;
    s.max = std::max(s.max, std::abs(e));
  }
  s.rms = std::sqrt(squares / static_cast<double>(errors.size()));
  s.mean = sum / static_cast<double>(errors.size());
  return s;
}

double mean(const std::vector<double>& values) {
  if (values.empty()) return 0;
  double sum = 0;
  for (double v : values) sum += v;
  return sum / static_cast<double>(values.size());
}

double standard_deviation(const std::vector<double>& values) {
  if (values.size() < 2) return 0;
  const double m = mean(values);
  double squares = 0;
  for (double v : values) squares += (v - m) * (v - m);
  return std::sqrt(squares / static_cast<double>(values.size() - 1));
}

}  // namespace ubersim::report
