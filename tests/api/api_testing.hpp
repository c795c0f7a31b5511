#pragma once
// What the tests of the library layer share: the repository's catalog, measurements by name, and a check
// that a call fails with InputError mentioning a text.
#include "petroscope/api/measurements.hpp"
#include "petroscope/core/error.hpp"
#include "petroscope/io/data_files.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <optional>
#include <string>

namespace petroscope {

inline const MineralCatalog& minerals() {
    static const MineralCatalog catalog = load_mineral_catalog(std::filesystem::path(PETROSCOPE_SOURCE_DIR) / "minerals");
    return catalog;
}

inline std::optional<double> measured(const Measurements& measurements, const std::string& name) {
    for (const Measurement& m : measurements) {
        if (m.name == name) return m.value;
    }
    ADD_FAILURE() << "no measurement " << name;
    return std::nullopt;
}

inline void expect_input_error(const std::function<void()>& call, const std::string& expected) {
    try {
        call();
        ADD_FAILURE() << "no error; expected one mentioning '" << expected << "'";
    } catch (const InputError& error) {
        EXPECT_NE(std::string(error.what()).find(expected), std::string::npos) << error.what();
    }
}

}  // namespace petroscope
