#include "petroscope/verification/report.hpp"

#include <algorithm>
#include <cmath>

namespace petroscope {

bool VerificationTest::passed() const {
    return !checks.empty() && std::all_of(checks.begin(), checks.end(), [](const VerificationCheck& c) { return c.passed; });
}

void VerificationTest::check(const std::string& quantity, double measured, double expected, double tolerance) {
    const bool ok = std::isfinite(measured) && std::abs(measured - expected) <= tolerance;
    checks.push_back({quantity, measured, expected, tolerance, ok});
}

int VerificationReport::passed_count() const {
    return static_cast<int>(std::count_if(tests.begin(), tests.end(), [](const VerificationTest& t) { return t.passed(); }));
}

int VerificationReport::failed_count() const { return static_cast<int>(tests.size()) - passed_count(); }

nlohmann::json report_json(const VerificationReport& report) {
    nlohmann::json tests = nlohmann::json::array();
    for (const VerificationTest& test : report.tests) {
        nlohmann::json checks = nlohmann::json::array();
        for (const VerificationCheck& c : test.checks) {
            checks.push_back({{"quantity", c.quantity}, {"measured", c.measured}, {"expected", c.expected},
                              {"tolerance", c.tolerance}, {"passed", c.passed}});
        }
        tests.push_back({{"name", test.name}, {"statement", test.statement}, {"source", test.source},
                         {"passed", test.passed()}, {"checks", checks}});
    }
    return {{"tests", tests}, {"passed", report.passed_count()}, {"failed", report.failed_count()}};
}

}  // namespace petroscope
