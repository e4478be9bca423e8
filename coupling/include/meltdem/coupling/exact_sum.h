#pragma once
// Compensated (double-double) running sum for conservation ledgers: totals of many small
// transfers stay exact to ~1e-32 relative, so "mass handed over == initial mass" holds to
// the last bit of a double instead of drifting by one rounding per step.

namespace meltdem::coupling {

class ExactSum {
 public:
  // add x (Knuth's TwoSum keeps the rounding error of every addition)
  void add(double x)
  {
    const double s = hi_ + x;
    const double bp = s - hi_;
    const double err = (hi_ - (s - bp)) + (x - bp);
    hi_ = s;
    lo_ += err;
  }
  // add a - b without rounding it first (the exact difference is split into two doubles)
  void add_difference(double a, double b)
  {
    const double s = a - b;
    const double bp = s - a;
    const double err = (a - (s - bp)) + (-b - bp);
    add(s);
    lo_ += err;
  }
  double value() const { return hi_ + lo_; }
  double hi() const { return hi_; }
  double lo() const { return lo_; }
  void set(double hi, double lo)
  {
    hi_ = hi;
    lo_ = lo;
  }

 private:
  double hi_ = 0.0, lo_ = 0.0;
};

}  // namespace meltdem::coupling
