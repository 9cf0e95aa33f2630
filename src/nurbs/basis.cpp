#include "nurbs/basis.h"

#include <cmath>
#include <sstream>
#include <string>

#include "core/error.h"

namespace hm {
namespace {

[[noreturn]] void fail(const char* what, const std::string& message) {
  throw GeometryError(std::string(what) + ": " + message);
}

}  // namespace

void check_direction(const char* what, int degree, long long count, std::span<const double> knots,
                     double t0, double t1) {
  if (degree < 1) fail(what, "degree " + std::to_string(degree) + " is below 1");
  if (degree > kernel::kMaxDegree) {
    fail(what, "degree " + std::to_string(degree) + " exceeds the maximum " +
                   std::to_string(kernel::kMaxDegree));
  }
  if (count <= degree) {
    fail(what, "degree " + std::to_string(degree) + " needs at least " +
                   std::to_string(degree + 1) + " control points, the net has " +
                   std::to_string(count));
  }
  const long long expected = count + degree + 1;
  if (static_cast<long long>(knots.size()) != expected) {
    fail(what, "knot vector has " + std::to_string(knots.size()) + " values, expected count + " +
                   "degree + 1 = " + std::to_string(expected));
  }
  for (std::size_t i = 0; i < knots.size(); ++i) {
    if (!std::isfinite(knots[i])) fail(what, "knot " + std::to_string(i) + " is not finite");
    if (i > 0 && knots[i] < knots[i - 1]) {
      std::ostringstream os;
      os.precision(17);
      os << "knots decrease at index " << i << " (" << knots[i - 1] << " then " << knots[i] << ")";
      fail(what, os.str());
    }
  }
  const double lo = knots[degree];
  const double hi = knots[count];
  if (!(lo < hi)) fail(what, "the valid knot range [knots[degree], knots[count]] is empty");
  if (!std::isfinite(t0) || !std::isfinite(t1) || !(t0 < t1)) {
    std::ostringstream os;
    os.precision(17);
    os << "parameter domain [" << t0 << ", " << t1 << "] is empty or not finite";
    fail(what, os.str());
  }
  const double tol = 1e-9 * (hi - lo);
  if (t0 < lo - tol || t1 > hi + tol) {
    std::ostringstream os;
    os.precision(17);
    os << "parameter domain [" << t0 << ", " << t1 << "] is outside the knot range [" << lo << ", "
       << hi << "]";
    fail(what, os.str());
  }
}

void check_net(const char* what, std::span<const Vec3d> points, std::span<const double> weights,
               long long expected) {
  if (static_cast<long long>(points.size()) != expected) {
    fail(what, "has " + std::to_string(points.size()) + " control points, expected " +
                   std::to_string(expected));
  }
  if (weights.size() != points.size()) {
    fail(what, "has " + std::to_string(weights.size()) + " weights for " +
                   std::to_string(points.size()) + " control points");
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!is_finite(points[i])) fail(what, "control point " + std::to_string(i) + " is not finite");
    if (!std::isfinite(weights[i]) || !(weights[i] > 0)) {
      std::ostringstream os;
      os.precision(17);
      os << "weight " << i << " is " << weights[i] << ", weights must be positive and finite";
      fail(what, os.str());
    }
  }
}

std::vector<double> span_breaks(std::span<const double> knots, double t0, double t1) {
  std::vector<double> out{t0};
  for (const double k : knots) {
    if (k > t0 && k < t1 && k > out.back()) out.push_back(k);
  }
  out.push_back(t1);
  return out;
}

}  // namespace hm
