// The wavelength grid (include/petroscope/spectral/wavelength_grid.hpp): the default 380–780 nm every 5 nm,
// "START:END:STEP" parsing, and errors that quote the bad text.
#include "petroscope/spectral/wavelength_grid.hpp"

#include "petroscope/core/error.hpp"

#include <gtest/gtest.h>

#include <string>

namespace petroscope {
namespace {

TEST(WavelengthGrid, DefaultIs380To780Every5nm) {
    const WavelengthGrid grid{};
    EXPECT_EQ(grid.size(), 81);
    const auto wavelengths = grid.wavelengths_nm();
    ASSERT_EQ(wavelengths.size(), 81u);
    EXPECT_EQ(wavelengths.front(), 380.0);
    EXPECT_EQ(wavelengths.back(), 780.0);
    // start + step·i with integer-valued doubles is exact.
    for (std::size_t i = 0; i < wavelengths.size(); ++i) EXPECT_EQ(wavelengths[i], 380.0 + 5.0 * static_cast<double>(i));
}

TEST(WavelengthGrid, ParseGivesTheDefault) {
    const WavelengthGrid grid = WavelengthGrid::parse("380:780:5");
    EXPECT_EQ(grid.start_nm, 380.0);
    EXPECT_EQ(grid.end_nm, 780.0);
    EXPECT_EQ(grid.step_nm, 5.0);
    EXPECT_EQ(grid.wavelengths_nm(), WavelengthGrid{}.wavelengths_nm());
}

TEST(WavelengthGrid, ParseOtherGrids) {
    EXPECT_EQ(WavelengthGrid::parse("400:700:10").size(), 31);
    EXPECT_EQ(WavelengthGrid::parse(" 380 : 780 : 1 ").size(), 401);  // parts are trimmed
    EXPECT_EQ(WavelengthGrid::parse("589.3:589.3:1").size(), 1);        // START = END is one wavelength
    // END is not on the grid: the last sample is the largest one <= END.
    const auto uneven = WavelengthGrid::parse("380:782:5").wavelengths_nm();
    EXPECT_EQ(uneven.size(), 81u);
    EXPECT_EQ(uneven.back(), 780.0);
}

TEST(WavelengthGrid, EndIsKeptDespiteRoundingOfTheStepCount) {
    // (0.3 − 0.1)/0.1 = 1.9999999999999998 in doubles; the grid must still hold 0.1, 0.2, 0.3.
    const WavelengthGrid grid = WavelengthGrid::parse("0.1:0.3:0.1");
    EXPECT_EQ(grid.size(), 3);
    EXPECT_NEAR(grid.wavelengths_nm().back(), 0.3, 1e-15);
}

TEST(WavelengthGrid, Monochromatic) {
    const WavelengthGrid grid = WavelengthGrid::monochromatic(589.3);
    EXPECT_EQ(grid.size(), 1);
    EXPECT_EQ(grid.wavelengths_nm(), std::vector<double>{589.3});
}

TEST(WavelengthGrid, ParseErrorsQuoteTheBadText) {
    for (const std::string bad : {"380:780", "a:b:c", "380:780:0", "780:380:5", "-1:10:1", "380:780:-5", "",
                                  "380:780:5:1", "380:780:5nm", "0:780:5", "nan:780:5", "1:100000:0.5"}) {
        SCOPED_TRACE("text: '" + bad + "'");
        try {
            WavelengthGrid::parse(bad);
            ADD_FAILURE() << "no error for '" << bad << "'";
        } catch (const InputError& e) {
            const std::string message = e.what();
            EXPECT_NE(message.find("'" + bad + "'"), std::string::npos) << message;
            EXPECT_NE(message.find("START:END:STEP"), std::string::npos) << message;
        }
    }
}

TEST(WavelengthGrid, HugeSampleCountsAreRejected) {
    // Was a bug: size() converts floor((END − START)/STEP) to int; for 1e300 (or 4e302) samples the conversion is
    // out of range (undefined behaviour; on x86-64 it gives INT_MIN), so size() is negative, the "more than
    // 100000 wavelengths" check passes, and the grid is accepted. `petroscope conoscope --wavelengths
    // 1:1e300:1` then ends with "internal error: cannot create std::vector larger than max_size()", exit 3.
    for (const std::string bad : {"1:1e300:1", "380:780:1e-300", "1:3e9:1"}) {
        SCOPED_TRACE(bad);
        EXPECT_THROW(WavelengthGrid::parse(bad), InputError);
    }
}

}  // namespace
}  // namespace petroscope
