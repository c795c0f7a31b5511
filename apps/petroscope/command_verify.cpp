// petroscope verify [--json] [--cases DIR]: the verification suite of the interface model.
#include "cli_common.hpp"

#include "petroscope/io/data_files.hpp"
#include "petroscope/verification/interface_cases.hpp"
#include "petroscope/verification/interface_suite.hpp"

#include <cstdio>
#include <iostream>
#include <memory>

namespace petroscope::cli {
namespace {

struct VerifyOptions {
    bool json = false;
    std::string cases_dir;
};

void print_report(const VerificationReport& report) {
    for (const VerificationTest& test : report.tests) {
        std::printf("%s  %s\n", test.passed() ? "PASS" : "FAIL", test.name.c_str());
        if (!test.statement.empty()) std::printf("      %s\n", test.statement.c_str());
        if (!test.source.empty()) std::printf("      source: %s\n", test.source.c_str());
        for (const VerificationCheck& check : test.checks) {
            if (check.passed && test.checks.size() > 6) continue;  // long lists: failures only
            std::printf("      %s %-52s measured %.15g, expected %.15g, tolerance %.3g\n", check.passed ? "ok  " : "FAIL",
                        check.quantity.c_str(), check.measured, check.expected, check.tolerance);
        }
    }
    std::printf("verify: %d passed, %d failed\n", report.passed_count(), report.failed_count());
}

}  // namespace

void add_verify_command(CLI::App& app, const std::string& minerals_dir) {
    auto options = std::make_shared<VerifyOptions>();
    CLI::App* command = app.add_subcommand(
        "verify",
        "Run the verification suite of the local interface model: the numerical tests of the paper\n"
        "\"Verification of algorithms of photorealistic rendering of crystals\" (corrected where the paper is\n"
        "wrong) from the shareable case files, and petroscope's own sweeps. Exit code 1 if any test fails.\n"
        "The tests are described in docs/verification.md.");
    command->add_flag("--json", options->json, "Print the report as JSON");
    command->add_option("--cases", options->cases_dir, "Folder of case files (default: verification/cases of the source tree)");
    command->callback([options, &minerals_dir] {
        const MineralCatalog catalog = load_mineral_catalog(minerals_directory(minerals_dir));
        const std::filesystem::path cases = options->cases_dir.empty() ? data_directory().parent_path() / "verification" / "cases"
                                                                       : std::filesystem::path(options->cases_dir);
        VerificationReport report = check_case_directory(cases, catalog);
        for (VerificationTest& test : run_interface_suite(InterfaceSuiteSize{})) report.tests.push_back(std::move(test));
        if (options->json) {
            std::cout << report_json(report).dump(2) << '\n';
        } else {
            print_report(report);
        }
        if (report.failed_count() > 0) throw ExitCode{1};
    });
}

}  // namespace petroscope::cli
