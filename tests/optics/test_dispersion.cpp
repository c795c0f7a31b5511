// Dispersion models of minerals/README.md (include/petroscope/optics/dispersion.hpp) against values computed
// by hand or by an independent Python evaluation of the refractiveindex.info formulas.
#include "petroscope/optics/dispersion.hpp"

#include "petroscope/core/error.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace petroscope {
namespace {

// Reference values are double-precision evaluations of the same formula in another order of operations; a
// few roundings of numbers near 2 differ by ~1e-15, so 1e-13 is a safe bound that still checks every digit
// that matters (and the formula: a wrong pole convention changes n in the 3rd–5th decimal).
constexpr double kFormulaTolerance = 1e-13;

std::string parse_error(const std::string& text) {
    try {
        DispersionModel::parse(text);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

TEST(Dispersion, Constant) {
    const DispersionModel model = DispersionModel::parse("constant 1.544");
    EXPECT_EQ(model.kind(), DispersionModel::Kind::constant);
    EXPECT_EQ(model.coefficients(), std::vector<double>{1.544});
    for (const double nm : {200.0, 589.3, 2000.0}) EXPECT_EQ(model(nm), 1.544);
    EXPECT_EQ(DispersionModel::constant(2.0)(400.0), 2.0);
    EXPECT_EQ(DispersionModel::constant(2.0).kind(), DispersionModel::Kind::constant);
}

TEST(Dispersion, CauchyTwoToFourTerms) {
    // n = A + B/λ² + C/λ⁴ + D/λ⁶, λ in µm.
    // 500 nm: 1.5 + 0.004/0.25 = 1.516.
    EXPECT_NEAR(DispersionModel::parse("cauchy 1.5 0.004")(500.0), 1.516, 1e-15);
    // 400 nm: 1.5 + 0.004/0.16 + 0.0002/0.0256 = 1.5328125.
    EXPECT_NEAR(DispersionModel::parse("cauchy 1.5 0.004 0.0002")(400.0), 1.5328125, 1e-15);
    // 400 nm, four terms: 1.5 + 0.025 + 0.0078125 + 0.00001/0.004096 = 1.53525390625.
    EXPECT_NEAR(DispersionModel::parse("cauchy 1.5 0.004 0.0002 0.00001")(400.0), 1.53525390625, 1e-15);
    // At 1 µm every term counts with weight 1.
    EXPECT_NEAR(DispersionModel::parse("cauchy 1.5 0.004 0.0002 0.00001")(1000.0), 1.50421, 1e-15);
}

TEST(Dispersion, RiiFormula1SapphireMalitsonOrdinary) {
    // main_Al2O3_nk_Malitson-o.yml: formula 1, coefficients 0 1.4313493 0.0726631 0.65054713 0.1193242 5.3414021 18.028251
    const DispersionModel model =
        DispersionModel::parse("rii-formula-1 0 1.4313493 0.0726631 0.65054713 0.1193242 5.3414021 18.028251");
    EXPECT_EQ(model.kind(), DispersionModel::Kind::rii_formula_1);
    // python3: c=[0,1.4313493,0.0726631,0.65054713,0.1193242,5.3414021,18.028251];
    //   math.sqrt(1+c[0]+sum(c[i]*l*l/(l*l-c[i+1]**2) for i in range(1,len(c)-1,2)))
    EXPECT_NEAR(model(589.3), 1.7680763548650107, kFormulaTolerance);  // l = 0.5893
    EXPECT_NEAR(model(400.0), 1.7865212049974144, kFormulaTolerance);  // l = 0.4
}

TEST(Dispersion, RiiFormula2QuartzGhosh) {
    // main_SiO2_nk_Ghosh-o.yml / -e.yml: formula 2.
    const DispersionModel ordinary = DispersionModel::parse("rii-formula-2 0.28604141 1.07044083 1.00585997e-2 1.10202242 100");
    const DispersionModel extraordinary =
        DispersionModel::parse("rii-formula-2 0.28851804 1.09509924 1.02101864e-2 1.15662475 100");
    EXPECT_EQ(ordinary.kind(), DispersionModel::Kind::rii_formula_2);
    // python3: c=[0.28604141,1.07044083,1.00585997e-2,1.10202242,100];
    //   math.sqrt(1+c[0]+sum(c[i]*l*l/(l*l-c[i+1]) for i in range(1,len(c)-1,2)))
    EXPECT_NEAR(ordinary(589.3), 1.5442057387841213, kFormulaTolerance);  // l = 0.5893 (handbook ω = 1.5443)
    EXPECT_NEAR(ordinary(400.0), 1.557730765267995, kFormulaTolerance);   // l = 0.4
    // same line with c=[0.28851804,1.09509924,1.02101864e-2,1.15662475,100]
    EXPECT_NEAR(extraordinary(589.3), 1.5533057742676768, kFormulaTolerance);  // l = 0.5893 (handbook ε = 1.5534)
}

TEST(Dispersion, RiiFormula4WithAndWithoutPowerTerms) {
    // main_BaB2O4_nk_Eimerl-o.yml: formula 4 with one power term (C10 λ^C11).
    const DispersionModel bbo = DispersionModel::parse("rii-formula-4 2.7405 0.0184 0 0.0179 1 0 0 0 1 -0.0155 2");
    EXPECT_EQ(bbo.kind(), DispersionModel::Kind::rii_formula_4);
    // python3: c=[2.7405,0.0184,0,0.0179,1,0,0,0,1,-0.0155,2];
    //   math.sqrt(c[0]+c[1]*l**c[2]/(l*l-c[3]**c[4])+c[5]*l**c[6]/(l*l-c[7]**c[8])
    //             +sum(c[i]*l**c[i+1] for i in range(9,len(c)-1,2)))
    EXPECT_NEAR(bbo(589.3), 1.6706228507692498, kFormulaTolerance);  // l = 0.5893
    EXPECT_NEAR(bbo(700.0), 1.6648963311497682, kFormulaTolerance);  // l = 0.7

    // main_KTiOPO4_nk_Kato-alpha.yml: exactly nine coefficients (no power terms).
    const DispersionModel ktp = DispersionModel::parse("rii-formula-4 3.29100 0.04140 0 0.03978 1 9.35522 0 31.45571 1");
    // same python line with c=[3.29100,0.04140,0,0.03978,1,9.35522,0,31.45571,1]
    EXPECT_NEAR(ktp(589.3), 1.7677407037481134, kFormulaTolerance);  // l = 0.5893
    EXPECT_NEAR(ktp(450.0), 1.801690452487606, kFormulaTolerance);   // l = 0.45
}

TEST(Dispersion, TableInterpolatesLinearlyAndExtrapolatesConstant) {
    const DispersionModel table = DispersionModel::parse("table-nm 400:1.5 500:1.6 600:1.55");
    EXPECT_EQ(table.kind(), DispersionModel::Kind::table_nm);
    EXPECT_EQ(table.coefficients(), (std::vector<double>{400, 1.5, 500, 1.6, 600, 1.55}));
    EXPECT_EQ(table(400.0), 1.5);
    EXPECT_EQ(table(500.0), 1.6);
    EXPECT_EQ(table(600.0), 1.55);
    EXPECT_NEAR(table(450.0), 1.55, 1e-15);
    EXPECT_NEAR(table(425.0), 1.525, 1e-15);
    EXPECT_NEAR(table(550.0), 1.575, 1e-15);
    EXPECT_NEAR(table(590.0), 1.555, 1e-15);
    // Constant beyond the ends.
    EXPECT_EQ(table(300.0), 1.5);
    EXPECT_EQ(table(399.999), 1.5);
    EXPECT_EQ(table(600.001), 1.55);
    EXPECT_EQ(table(2000.0), 1.55);
    // Two points are enough.
    EXPECT_NEAR(DispersionModel::parse("table-nm 400:0.001 700:0.004")(500.0), 0.002, 1e-15);
}

TEST(Dispersion, DrudeRotatoryDispersionSumsItsTerms) {
    // Σ Kᵢ/(λ² − Lᵢ²) with λ and Lᵢ in µm.
    const DispersionModel one = DispersionModel::parse("drude 7.16 0.13");
    EXPECT_NEAR(one(589.3), 7.16 / (0.5893 * 0.5893 - 0.13 * 0.13), 1e-13);
    const DispersionModel two = DispersionModel::parse("drude 7.16 0.13 -0.5 0.2");
    EXPECT_NEAR(two(500.0), 7.16 / (0.25 - 0.0169) - 0.5 / (0.25 - 0.04), 1e-13);
    EXPECT_EQ(DispersionModel::parse(two.describe()).coefficients(), two.coefficients());
}

TEST(Dispersion, UnknownModelListsTheValidOnes) {
    const std::string message = parse_error("sellmeier 1 2 3");
    EXPECT_NE(message.find("'sellmeier'"), std::string::npos) << message;
    for (const char* name : {"constant", "cauchy", "rii-formula-1", "rii-formula-2", "rii-formula-4", "table-nm", "drude"}) {
        EXPECT_NE(message.find(name), std::string::npos) << name << " missing from: " << message;
    }
    EXPECT_FALSE(parse_error("").empty());
    EXPECT_FALSE(parse_error("   ").empty());
    EXPECT_FALSE(parse_error("rii-formula-3 1 2 3").empty());
}

TEST(Dispersion, WrongCoefficientCountsAreErrorsNamingTheModel) {
    const std::vector<std::pair<std::string, std::string>> cases{
        {"constant", "constant"},
        {"constant 1.5 1.6", "constant"},
        {"cauchy 1.5", "cauchy"},
        {"cauchy 1.5 0.1 0.2 0.3 0.4", "cauchy"},
        {"rii-formula-1 0 1", "rii-formula-1"},
        {"rii-formula-1", "rii-formula-1"},
        {"rii-formula-1 0 1 0.1 1", "rii-formula-1"},
        {"rii-formula-2 0 1 0.01 1", "rii-formula-2"},
        {"rii-formula-4 1 2 3 4 5 6 7 8", "rii-formula-4"},
        {"rii-formula-4 1 0 0 0 1 0 0 0 1 1", "rii-formula-4"},
        {"table-nm 500:1.5", "table-nm"},
        {"table-nm", "table-nm"},
        {"drude 7.16", "drude"},
        {"drude 7.16 0.13 1.0", "drude"},
    };
    for (const auto& [text, model] : cases) {
        SCOPED_TRACE(text);
        const std::string message = parse_error(text);
        EXPECT_NE(message.find("'" + model + "'"), std::string::npos) << message;
        EXPECT_NE(message.find("expected"), std::string::npos) << message;
    }
}

TEST(Dispersion, BadNumbersAreErrorsQuotingThem) {
    for (const auto& [text, bad] : std::vector<std::pair<std::string, std::string>>{
             {"cauchy 1.5 abc", "'abc'"},
             {"constant nan", "'nan'"},
             {"constant inf", "'inf'"},
             {"cauchy 1.5 0.004x", "'0.004x'"},
             {"table-nm 400-1.5 500:1.6", "'400-1.5'"},
             {"table-nm 400:1.5 500:x", "'500:x'"},
             {"table-nm 400:1.5:2 500:1.6", "'400:1.5:2'"},
             {"table-nm -400:1.5 500:1.6", "'-400:1.5'"},
             {"table-nm 0:1.5 500:1.6", "'0:1.5'"}}) {
        SCOPED_TRACE(text);
        const std::string message = parse_error(text);
        EXPECT_NE(message.find(bad), std::string::npos) << message;
    }
}

TEST(Dispersion, TableWavelengthsMustIncrease) {
    for (const std::string text : {"table-nm 500:1.5 400:1.6", "table-nm 400:1.5 400:1.6", "table-nm 400:1.5 600:1.6 500:1.7"}) {
        SCOPED_TRACE(text);
        const std::string message = parse_error(text);
        EXPECT_NE(message.find("increasing"), std::string::npos) << message;
    }
}

TEST(Dispersion, DescribeRoundTripsThroughParse) {
    const std::vector<DispersionModel> models{
        DispersionModel::constant(1.0 / 3.0),
        DispersionModel::constant(1.5442057387841213),
        DispersionModel::parse("cauchy 1.54508385 0.00518"),
        DispersionModel::parse("cauchy 1.5 0.004 0.0002 0.00001"),
        DispersionModel::parse("rii-formula-1 0 1.4313493 0.0726631 0.65054713 0.1193242 5.3414021 18.028251"),
        DispersionModel::parse("rii-formula-2 0.28604141 1.07044083 1.00585997e-2 1.10202242 100"),
        DispersionModel::parse("rii-formula-4 2.7405 0.0184 0 0.0179 1 0 0 0 1 -0.0155 2"),
        DispersionModel::parse("table-nm 400:1.5 500.25:1.6 600:1e-7"),
    };
    for (const DispersionModel& model : models) {
        const std::string text = model.describe();
        SCOPED_TRACE(text);
        const DispersionModel again = DispersionModel::parse(text);
        EXPECT_EQ(again.kind(), model.kind());
        EXPECT_EQ(again.coefficients(), model.coefficients());  // bit-identical doubles
        for (const double nm : {380.0, 450.0, 589.3, 700.0, 780.0}) EXPECT_EQ(again(nm), model(nm));
        EXPECT_EQ(again.describe(), text);
    }
}

TEST(Dispersion, DescribeUsesTheFileSyntax) {
    EXPECT_EQ(DispersionModel::parse("cauchy 1.5 0.004").describe(), "cauchy 1.5 0.004");
    EXPECT_EQ(DispersionModel::parse("table-nm 400:1.5  500:1.6").describe(), "table-nm 400:1.5 500:1.6");
    EXPECT_EQ(DispersionModel::constant(2.0).describe(), "constant 2");
}

TEST(Dispersion, KindNames) {
    EXPECT_EQ(dispersion_kind_name(DispersionModel::Kind::constant), "constant");
    EXPECT_EQ(dispersion_kind_name(DispersionModel::Kind::cauchy), "cauchy");
    EXPECT_EQ(dispersion_kind_name(DispersionModel::Kind::rii_formula_1), "rii-formula-1");
    EXPECT_EQ(dispersion_kind_name(DispersionModel::Kind::rii_formula_2), "rii-formula-2");
    EXPECT_EQ(dispersion_kind_name(DispersionModel::Kind::rii_formula_4), "rii-formula-4");
    EXPECT_EQ(dispersion_kind_name(DispersionModel::Kind::table_nm), "table-nm");
}

}  // namespace
}  // namespace petroscope
