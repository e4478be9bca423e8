#pragma once
// Validation rows for GoogleTest: every comparison prints measured, reference and
// tolerance, asserts it, and appends the row to $MELTDEM_REPORT_DIR/<test>.tsv.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <string>

namespace meltdem::testing {

inline void report_row(const std::string &what, double measured, double reference, double tol,
                       const char *kind, bool ok)
{
  const auto *info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::string test = std::string(info->test_suite_name()) + "." + info->name();
  std::cout << std::setprecision(10) << "VALIDATION " << test << " | " << what << " | measured "
            << measured << " | reference " << reference << " | tolerance " << tol << " (" << kind
            << ") | " << (ok ? "PASS" : "FAIL") << std::endl;
  if (const char *dir = std::getenv("MELTDEM_REPORT_DIR")) {
    std::ofstream out(std::string(dir) + "/" + test + ".tsv", std::ios::app);
    out << std::setprecision(10) << test << '\t' << what << '\t' << measured << '\t' << reference
        << '\t' << tol << " " << kind << '\t' << (ok ? "PASS" : "FAIL") << '\n';
  }
}

// |measured - reference| <= tol * |reference|
inline void expect_relative(const std::string &what, double measured, double reference, double tol)
{
  const bool ok = std::abs(measured - reference) <= tol * std::abs(reference);
  report_row(what, measured, reference, tol, "relative", ok);
  EXPECT_TRUE(ok) << what << ": measured " << measured << " vs reference " << reference
                  << " exceeds relative tolerance " << tol;
}

// |measured - reference| <= tol
inline void expect_absolute(const std::string &what, double measured, double reference, double tol)
{
  const bool ok = std::abs(measured - reference) <= tol;
  report_row(what, measured, reference, tol, "absolute", ok);
  EXPECT_TRUE(ok) << what << ": measured " << measured << " vs reference " << reference
                  << " exceeds absolute tolerance " << tol;
}

}  // namespace meltdem::testing
