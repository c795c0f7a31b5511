#pragma once
// Checking the interface model against the shareable cases of verification/cases (format and matching
// rules: verification/cases/README.md).
#include "petroscope/io/interface_case.hpp"
#include "petroscope/verification/report.hpp"

#include <filesystem>

namespace petroscope {

/// Solves the case and compares every wave with the case's "expected" block.
VerificationTest check_interface_case(const InterfaceCase& interface_case);

/// Every *.json case in `directory`, in name order.
VerificationReport check_case_directory(const std::filesystem::path& directory, const MineralCatalog& catalog);

}  // namespace petroscope
