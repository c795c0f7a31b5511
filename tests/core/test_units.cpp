// Parsing of user-typed physical quantities (include/petroscope/core/units.hpp): lengths always need a
// unit, wavelengths may be bare nanometres; every failure is an InputError that names the value.
#include "petroscope/core/units.hpp"

#include "petroscope/core/error.hpp"

#include <gtest/gtest.h>

#include <string>

namespace petroscope {
namespace {

// The message of the InputError thrown by `parse` for `text`, or "" when nothing (or something else) is thrown.
template <typename Parse>
std::string input_error_message(Parse parse, const std::string& text) {
    try {
        parse(text);
    } catch (const InputError& e) {
        return e.what();
    } catch (...) {
        return "";
    }
    return "";
}

// Unit factors are powers of ten; a product such as 589 × 1e-3 is correctly rounded, so it may differ from
// the literal 0.589 by at most one rounding (EXPECT_DOUBLE_EQ allows 4 ulp).

TEST(ParseLength, MicrometresAreReturnedUnchanged) {
    EXPECT_EQ(parse_length_um("30um"), 30.0);
    EXPECT_EQ(parse_length_um("0.5um"), 0.5);
    EXPECT_EQ(parse_length_um("+30um"), 30.0);
}

TEST(ParseLength, MicroSignSuffixIsMicrometres) {
    // U+00B5 MICRO SIGN, as typed on most keyboards ("µm").
    EXPECT_EQ(parse_length_um("30\u00b5m"), 30.0);
    EXPECT_EQ(parse_length_um("2.5 \u00b5m"), 2.5);
}

TEST(ParseLength, OtherUnitsAreConvertedToMicrometres) {
    EXPECT_EQ(parse_length_um("1mm"), 1000.0);
    EXPECT_DOUBLE_EQ(parse_length_um("589nm"), 0.589);
    EXPECT_EQ(parse_length_um("2cm"), 20000.0);
    EXPECT_EQ(parse_length_um("1m"), 1e6);
    EXPECT_DOUBLE_EQ(parse_length_um("0.03mm"), 30.0);
    EXPECT_DOUBLE_EQ(parse_length_um("3e-3cm"), 30.0);
}

TEST(ParseLength, SpacesAroundAndBetweenNumberAndUnitAreAccepted) {
    // The header documents "1.5 mm": the text is trimmed, and the number before the unit is trimmed too.
    EXPECT_EQ(parse_length_um("1.5 mm"), 1500.0);
    EXPECT_EQ(parse_length_um("  30um  "), 30.0);
    EXPECT_EQ(parse_length_um("30\tum"), 30.0);
}

TEST(ParseLength, SignIsLeftToTheCaller) {
    // parse_length_um converts; whether a negative length is meaningful is decided by its callers (the CLI
    // rejects thickness <= 0, see tests/cli).
    EXPECT_EQ(parse_length_um("-5um"), -5.0);
    EXPECT_EQ(parse_length_um("0um"), 0.0);
}

TEST(ParseLength, RejectsMissingOrUnknownUnitsAndNonNumbers) {
    for (const std::string bad : {"30", "abc", "30 parsecs", "", "   ", "nan", "nanum", "infum", "1e400um", "um",
                                  "30 um um", "30um5", "thirty um", "1,5mm", "30uM", "0x1Aum",
                                  "30\u03bcm" /* Greek mu U+03BC is not the micro sign */}) {
        SCOPED_TRACE("text: '" + bad + "'");
        EXPECT_THROW(parse_length_um(bad), InputError);
    }
}

TEST(ParseLength, ErrorNamesTheValueAndTheAcceptedUnits) {
    const std::string message = input_error_message(parse_length_um, "30 parsecs");
    EXPECT_NE(message.find("'30 parsecs'"), std::string::npos) << message;
    for (const char* unit : {"nm", "um", "mm", "cm"}) EXPECT_NE(message.find(unit), std::string::npos) << message;

    const std::string bare = input_error_message(parse_length_um, "30");
    EXPECT_NE(bare.find("'30'"), std::string::npos) << bare;
    EXPECT_NE(bare.find("unit"), std::string::npos) << bare;
}

TEST(ParseLength, OverflowingUnitConversionIsAnError) {
    // Was a bug: "1e305" and "m" are each valid, but 1e305 m = 1e311 um overflows to +inf, and parse_length_um
    // returns inf instead of throwing (parse_double's "no Inf" guarantee is lost when the unit factor is applied).
    EXPECT_THROW(parse_length_um("1e305m"), InputError);
    EXPECT_THROW(parse_length_um("-1e305m"), InputError);
}

TEST(ParseWavelength, UnitsAndBareNanometres) {
    EXPECT_EQ(parse_wavelength_nm("589nm"), 589.0);
    EXPECT_DOUBLE_EQ(parse_wavelength_nm("0.5893um"), 589.3);
    EXPECT_DOUBLE_EQ(parse_wavelength_nm("0.5893\u00b5m"), 589.3);
    EXPECT_EQ(parse_wavelength_nm("589"), 589.0);
    EXPECT_DOUBLE_EQ(parse_wavelength_nm("589.3"), 589.3);
    EXPECT_EQ(parse_wavelength_nm(" 632.8 nm "), 632.8);
}

TEST(ParseWavelength, RejectsBadValuesAndLengthOnlyUnits) {
    // mm, cm and m are lengths, not wavelength units (units.hpp lists nm, um, µm).
    for (const std::string bad : {"", "nm", "abc", "589 parsecs", "589mm", "1m", "nan", "inf", "1e400", "1e400nm",
                                  "589nm nm", "5 89nm"}) {
        SCOPED_TRACE("text: '" + bad + "'");
        EXPECT_THROW(parse_wavelength_nm(bad), InputError);
    }
}

TEST(ParseWavelength, OverflowingUnitConversionIsAnError) {
    // Was a bug: 1e306 um = 1e309 nm overflows to +inf and is returned; `petroscope minerals show quartz
    // --wavelength 1e306um` then prints "at inf nm" with NaN indices and exits 0 (see tests/cli).
    EXPECT_THROW(parse_wavelength_nm("1e306um"), InputError);
}

TEST(ParseWavelength, ErrorNamesTheValue) {
    const std::string message = input_error_message(parse_wavelength_nm, "589 parsecs");
    EXPECT_NE(message.find("'589 parsecs'"), std::string::npos) << message;
    EXPECT_NE(message.find("wavelength"), std::string::npos) << message;
}

}  // namespace
}  // namespace petroscope
