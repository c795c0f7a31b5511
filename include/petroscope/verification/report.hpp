#pragma once
// The verification suite's report: each test's statement, the quantities it measured against their
// references and tolerances, and whether it passed.
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace petroscope {

struct VerificationCheck {
    std::string quantity;      // "power of reflected s+p", "max |r_s − closed form|", …
    double measured = 0.0;     // the measured value or deviation
    double expected = 0.0;     // the reference (0 for a deviation)
    double tolerance = 0.0;    // |measured − expected| ≤ tolerance passes
    bool passed = false;
};

struct VerificationTest {
    std::string name;
    std::string statement;  // what is tested, and, where the paper is wrong, the correct physics
    std::string source;     // the paper's section, a case file, or "petroscope"
    std::vector<VerificationCheck> checks;
    bool passed() const;
    void check(const std::string& quantity, double measured, double expected, double tolerance);
};

struct VerificationReport {
    std::vector<VerificationTest> tests;
    int passed_count() const;
    int failed_count() const;
};

/// {"tests": [{"name", "statement", "source", "passed", "checks": [{"quantity", "measured", "expected",
/// "tolerance", "passed"}]}], "passed": N, "failed": M}.
nlohmann::json report_json(const VerificationReport& report);

}  // namespace petroscope
