// Text helpers shared by the parsers (include/petroscope/core/text.hpp) and located errors (error.hpp).
#include "petroscope/core/text.hpp"

#include "petroscope/core/error.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace petroscope {
namespace {

using Words = std::vector<std::string>;

TEST(Trim, RemovesSpacesTabsAndLineEndsAtBothEnds) {
    EXPECT_EQ(trim("  \t a b \r\n"), "a b");
    EXPECT_EQ(trim("abc"), "abc");
    EXPECT_EQ(trim(""), "");
    EXPECT_EQ(trim(" \t\r\n "), "");
    EXPECT_EQ(trim("a \t b"), "a \t b");  // inner whitespace stays
}

TEST(ToLower, LowersAsciiOnly) {
    EXPECT_EQ(to_lower("KGd(WO4)2"), "kgd(wo4)2");
    EXPECT_EQ(to_lower("Iceland Spar"), "iceland spar");
    EXPECT_EQ(to_lower(""), "");
}

TEST(Split, SplitsOnTheSeparatorAndTrimsEachPart) {
    EXPECT_EQ(split("a, b ,c", ','), (Words{"a", "b", "c"}));
    EXPECT_EQ(split("380:780:5", ':'), (Words{"380", "780", "5"}));
    EXPECT_EQ(split("KGW, KGdW", ','), (Words{"KGW", "KGdW"}));
}

TEST(Split, KeepsEmptyPartsSoCallersCanRejectThem) {
    EXPECT_EQ(split("", ','), (Words{""}));
    EXPECT_EQ(split("a,,b", ','), (Words{"a", "", "b"}));
    EXPECT_EQ(split("a,", ','), (Words{"a", ""}));
    EXPECT_EQ(split(",a", ','), (Words{"", "a"}));
    EXPECT_EQ(split("no separator", ','), (Words{"no separator"}));
}

TEST(SplitWhitespace, SplitsOnRunsOfSpacesAndTabs) {
    EXPECT_EQ(split_whitespace(" cauchy\t1.53   0.0042 "), (Words{"cauchy", "1.53", "0.0042"}));
    EXPECT_EQ(split_whitespace(""), Words{});
    EXPECT_EQ(split_whitespace(" \t  "), Words{});
    EXPECT_EQ(split_whitespace("one"), (Words{"one"}));
}

TEST(ParseDouble, WholeTextAsAFiniteNumber) {
    EXPECT_EQ(parse_double("1.5"), 1.5);
    EXPECT_EQ(parse_double(" 2 "), 2.0);
    EXPECT_EQ(parse_double("+3"), 3.0);
    EXPECT_EQ(parse_double("-4.25"), -4.25);
    EXPECT_EQ(parse_double("1e3"), 1000.0);
    EXPECT_EQ(parse_double("1.00585997e-2"), 1.00585997e-2);
    EXPECT_EQ(parse_double(".5"), 0.5);
    EXPECT_EQ(parse_double("0"), 0.0);
}

TEST(ParseDouble, NoPartialParses) {
    for (const std::string bad : {"", "  ", "1.5x", "1.5 2", "x1.5", "1,5", "5e", "++3", "-+3", "0x10", ".",
                                  "e5", "1.5.2", "1.5um"}) {
        SCOPED_TRACE("text: '" + bad + "'");
        EXPECT_FALSE(parse_double(bad).has_value());
    }
}

TEST(ParseDouble, RejectsTwoSigns) {
    // Was a bug: parse_double strips one leading '+' and hands the rest to std::from_chars, which accepts a leading
    // '-', so "+-3" parses as -3 although it is not a number (strtod and every number syntax reject it).
    EXPECT_FALSE(parse_double("+-3").has_value());
    EXPECT_FALSE(parse_double("+-0.5e1").has_value());
}

TEST(ParseDouble, NoNanNoInfinityNoOverflow) {
    for (const std::string bad : {"nan", "NaN", "-nan", "nan(1)", "inf", "-inf", "+inf", "infinity", "INF", "1e400",
                                  "-1e400"}) {
        SCOPED_TRACE("text: '" + bad + "'");
        EXPECT_FALSE(parse_double(bad).has_value());
    }
}

TEST(EditDistance, LevenshteinDistances) {
    EXPECT_EQ(edit_distance("kitten", "sitting"), 3u);  // the textbook example: 2 substitutions + 1 insertion
    EXPECT_EQ(edit_distance("flaw", "lawn"), 2u);
    EXPECT_EQ(edit_distance("quarz", "quartz"), 1u);
    EXPECT_EQ(edit_distance("", "abc"), 3u);
    EXPECT_EQ(edit_distance("abc", ""), 3u);
    EXPECT_EQ(edit_distance("", ""), 0u);
    EXPECT_EQ(edit_distance("calcite", "calcite"), 0u);
    EXPECT_EQ(edit_distance("ab", "ba"), 2u);  // plain Levenshtein: no transpositions
}

TEST(EditDistance, IsSymmetric) {
    const std::vector<std::string> words{"quartz", "quarz", "calcite", "kalzit", "", "muscovite", "biotite"};
    for (const auto& a : words) {
        for (const auto& b : words) EXPECT_EQ(edit_distance(a, b), edit_distance(b, a)) << a << " / " << b;
    }
}

TEST(FormatWithUncertainty, RoundsSigmaToTwoDigitsAndValueToItsPlace) {
    EXPECT_EQ(format_with_uncertainty(39.97401, 0.0479925), "39.974 +- 0.048");
    EXPECT_EQ(format_with_uncertainty(299.9943, 0.18), "299.99 +- 0.18");
    EXPECT_EQ(format_with_uncertainty(1.06440, 0.0048899), "1.0644 +- 0.0049");
    EXPECT_EQ(format_with_uncertainty(1234.56, 12.3), "1235 +- 12");  // sigma >= 10: whole numbers
    EXPECT_EQ(format_with_uncertainty(2.5, 0.0), "2.5 +- 0");           // no rounding rule without a sigma
}

// Input quoted in a message never reaches the terminal as control characters, broken UTF-8 or invisible
// direction marks, and a long input is cut with its full length said.
TEST(QuoteInput, PrintableTextIsQuotedAsItIs) {
    EXPECT_EQ(quote_input("calcite"), "'calcite'");
    EXPECT_EQ(quote_input(""), "''");
    EXPECT_EQ(quote_input("Michel-L\u00e9vy 30 \u00b5m"), "'Michel-L\u00e9vy 30 \u00b5m'");  // UTF-8 letters stay
}

TEST(QuoteInput, ControlCharactersAndBytesThatAreNotUtf8AreEscaped) {
    EXPECT_EQ(quote_input("a\nb\tc\rd"), "'a\\nb\\tc\\rd'");
    EXPECT_EQ(quote_input(std::string("\x1b[31mred\x00\x7f", 10)), "'\\x1b[31mred\\x00\\x7f'");
    EXPECT_EQ(quote_input("\xff\xfe"), "'\\xff\\xfe'");              // not UTF-8
    EXPECT_EQ(quote_input("\xc3"), "'\\xc3'");                        // a sequence cut short
    EXPECT_EQ(quote_input("\xc0\xaf"), "'\\xc0\\xaf'");              // an overlong '/'
    EXPECT_EQ(quote_input("\xed\xa0\x80"), "'\\xed\\xa0\\x80'");    // a UTF-16 surrogate
    EXPECT_EQ(quote_input("\xc2\x85"), "'\\x85'");                    // C1 control NEL
}

TEST(QuoteInput, InvisibleLineAndDirectionControlsAreEscaped) {
    EXPECT_EQ(quote_input("abc\u202edef"), "'abc\\u202edef'");  // right-to-left override
    EXPECT_EQ(quote_input("a\u2028b\u2066c"), "'a\\u2028b\\u2066c'");
}

TEST(QuoteInput, LongTextIsCutAndItsLengthSaid) {
    const std::string long_text(5000, 'x');
    EXPECT_EQ(quote_input(long_text, 10), "'xxxxxxxxxx\u2026' (5000 bytes)");
    EXPECT_EQ(quote_input(std::string(80, 'y')), "'" + std::string(80, 'y') + "'");  // up to the limit: whole
    // The limit counts characters, not bytes: a multi-byte letter is never split.
    EXPECT_EQ(quote_input("\u00e9\u00e9\u00e9", 2), "'\u00e9\u00e9\u2026' (6 bytes)");
}

TEST(LocatedError, ReadsFileColonLineColonWhat) {
    const InputError error = located_error("minerals/quartz.txt", 12, "expected 'key: value'");
    EXPECT_STREQ(error.what(), "minerals/quartz.txt:12: expected 'key: value'");
}

}  // namespace
}  // namespace petroscope
