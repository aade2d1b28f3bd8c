// Values with units, sizes, paper names and choices (slicer/unit_values.h), and the same
// through the parameter tables (text from the CLI, strings in job files).
#include "slicer/unit_values.h"

#include <gtest/gtest.h>

#include "slicer/input_error.h"
#include "slicer/params.h"

namespace strand::slicer {
namespace {

struct QuantityCase {
  const char* text;
  const char* table_unit;
  double expected;  // exactly: the double nearest the converted value
};

// Every unit, exponent forms and spaces; each result compared with ==, not a tolerance.
TEST(ParseQuantity, EveryUnitConvertsExactly) {
  const QuantityCase cases[] = {
      {"0.84", "mm", 0.84},
      {"0.84mm", "mm", 0.84},
      {"0.84 mm", "mm", 0.84},
      {"  0.84  mm  ", "mm", 0.84},
      {"840um", "mm", 0.84},
      {"840 um", "mm", 0.84},
      {"840\xC2\xB5m", "mm", 0.84},  // µ, micro sign
      {"840\xCE\xBCm", "mm", 0.84},  // μ, Greek mu
      {"0.084cm", "mm", 0.84},
      {"0.00084m", "mm", 0.84},
      {"8.4e-1mm", "mm", 0.84},
      {"8.4E-1 mm", "mm", 0.84},
      {"84e-2", "mm", 0.84},
      {"8.4e2um", "mm", 0.84},
      {"+0.84mm", "mm", 0.84},
      {"-1.5cm", "mm", -15.0},
      {".5in", "mm", 12.7},
      {"1in", "mm", 25.4},
      {"0.3in", "mm", 7.62},
      {"36cm", "mm", 360.0},
      {"2m", "mm", 2000.0},
      {"250", "mm/min", 250.0},
      {"250mm/min", "mm/min", 250.0},
      {"250 mm/min", "mm/min", 250.0},
      {"25mm/s", "mm/min", 1500.0},
      {"0.1mm/s", "mm/min", 6.0},
      {"4.2e1 mm/s", "mm/min", 2520.0},
      {"90", "deg", 90.0},
      {"90deg", "deg", 90.0},
      {"90\xC2\xB0", "deg", 90.0},  // °
      {"0rad", "deg", 0.0},
      {"3", "px", 3.0},
      {"3px", "px", 3.0},
      {"7", "", 7.0},
      {"1e3", "", 1000.0},
  };
  for (const auto& c : cases) {
    const UnitValues u = parse_quantity(c.text, c.table_unit);
    ASSERT_TRUE(u.ok()) << c.text << ": " << u.unit_problem;
    ASSERT_EQ(u.values.size(), 1u) << c.text;
    EXPECT_EQ(u.values[0], c.expected) << c.text << " in " << c.table_unit;
  }
}

TEST(ParseQuantity, RadiansBecomeDegreesWithinOneUlp) {
  const UnitValues u = parse_quantity("1.5707963267948966rad", "deg");
  ASSERT_TRUE(u.ok());
  EXPECT_NEAR(u.values[0], 90.0, 2e-14);
  EXPECT_DOUBLE_EQ(parse_quantity("1 rad", "deg").values.at(0), 57.295779513082323);
}

struct RefusedCase {
  const char* text;
  const char* table_unit;
  const char* problem;  // empty: malformed (no number at all)
};

TEST(ParseQuantity, WrongDimensionsUnknownUnitsAndUnitsOnPlainNumbersAreRefused) {
  const RefusedCase cases[] = {
      {"3mm/s", "mm", "expected a length (mm, cm, m, um, in)"},
      {"3deg", "mm", "expected a length (mm, cm, m, um, in)"},
      {"3px", "mm", "expected a length (mm, cm, m, um, in)"},
      {"3 furlong", "mm", "expected a length (mm, cm, m, um, in)"},
      {"3mmm", "mm", "expected a length (mm, cm, m, um, in)"},
      {"3mm/h", "mm", "expected a length (mm, cm, m, um, in)"},
      {"2em", "mm", "expected a length (mm, cm, m, um, in)"},
      {"250mm", "mm/min", "expected a speed (mm/min, mm/s)"},
      {"250 in", "mm/min", "expected a speed (mm/min, mm/s)"},
      {"1mm", "deg", "expected an angle (deg, rad)"},
      {"3mm", "px", "expected pixels (px)"},
      {"3mm", "", "expected a plain number (no unit)"},
      {"3deg", "", "expected a plain number (no unit)"},
      {"", "mm", ""},
      {"mm", "mm", ""},
      {"abc", "mm", ""},
      {"1,5", "mm", ""},
      {"0.84 0.84", "mm", ""},
      {"inf", "mm", ""},
      {"nan", "", ""},
      {"1e999", "mm", ""},
      {"1e400um", "mm", ""},
      {".", "mm", ""},
      {"-", "", ""},
  };
  for (const auto& c : cases) {
    const UnitValues u = parse_quantity(c.text, c.table_unit);
    EXPECT_FALSE(u.ok()) << c.text;
    EXPECT_TRUE(u.values.empty()) << c.text;
    if (*c.problem) {
      EXPECT_EQ(u.unit_problem, c.problem) << c.text;
    } else {
      EXPECT_TRUE(u.malformed) << c.text << ": " << u.unit_problem;
    }
  }
}

TEST(ParseQuantity, TinyValuesUnderflowToZeroNotToAnError) {
  const UnitValues u = parse_quantity("1e-400mm", "mm");
  ASSERT_TRUE(u.ok());
  EXPECT_EQ(u.values.at(0), 0.0);
}

TEST(ParseQuantities, SizesTakeOneUnitAfterTheLastOrOneEach) {
  const std::vector<double> size = {36.0, 36.0};
  for (const char* text : {"36x36", "36x36mm", "36 x 36", "36 x 36 mm", "36mmx36mm",
                           "36mm x 36mm", "3.6cmx36mm", "36X36", "36\xC3\x97" "36", "3.6x3.6cm",
                           "3.6e1x360e-1mm"}) {
    const UnitValues u = parse_quantities(text, "mm", 'x');
    ASSERT_TRUE(u.ok()) << text << ": " << u.unit_problem;
    EXPECT_EQ(u.values, size) << text;
  }
  EXPECT_EQ(parse_quantities("1inx2in", "mm", 'x').values, (std::vector<double>{25.4, 50.8}));
  EXPECT_EQ(parse_quantities("0,90deg", "deg", ',').values, (std::vector<double>{0.0, 90.0}));
  EXPECT_EQ(parse_quantities("0, 90", "deg", ',').values, (std::vector<double>{0.0, 90.0}));
  EXPECT_EQ(parse_quantities("0.5mm,1mm,250um", "mm", ',').values,
            (std::vector<double>{0.5, 1.0, 0.25}));
}

TEST(ParseQuantities, AmbiguousOrWrongUnitsAndBadShapesAreRefused) {
  EXPECT_EQ(parse_quantities("36cm x 36", "mm", 'x').unit_problem,
            "give the unit after every number, or once after the last");
  EXPECT_EQ(parse_quantities("36x36mm/s", "mm", 'x').unit_problem,
            "expected a length (mm, cm, m, um, in)");
  EXPECT_EQ(parse_quantities("0,90mm", "deg", ',').unit_problem, "expected an angle (deg, rad)");
  for (const char* text : {"36x", "x36", "36xx36", "36 36", "36x36x", ""}) {
    EXPECT_TRUE(parse_quantities(text, "mm", 'x').malformed) << text;
  }
}

TEST(PaperSize, NamesInAnyCasePortraitUnlessLandscape) {
  using Size = std::array<double, 2>;
  EXPECT_EQ(paper_size_mm("A4"), (Size{210, 297}));
  EXPECT_EQ(paper_size_mm("a4"), (Size{210, 297}));
  EXPECT_EQ(paper_size_mm("A4 portrait"), (Size{210, 297}));
  EXPECT_EQ(paper_size_mm("A4 landscape"), (Size{297, 210}));
  EXPECT_EQ(paper_size_mm("a4-landscape"), (Size{297, 210}));
  EXPECT_EQ(paper_size_mm("A4_Landscape"), (Size{297, 210}));
  EXPECT_EQ(paper_size_mm(" A4  -  LANDSCAPE "), (Size{297, 210}));
  EXPECT_EQ(paper_size_mm("A0"), (Size{841, 1189}));
  EXPECT_EQ(paper_size_mm("A1"), (Size{594, 841}));
  EXPECT_EQ(paper_size_mm("A2"), (Size{420, 594}));
  EXPECT_EQ(paper_size_mm("A3"), (Size{297, 420}));
  EXPECT_EQ(paper_size_mm("A5"), (Size{148, 210}));
  EXPECT_EQ(paper_size_mm("A6"), (Size{105, 148}));
  EXPECT_EQ(paper_size_mm("Letter"), (Size{215.9, 279.4}));
  EXPECT_EQ(paper_size_mm("letter landscape"), (Size{279.4, 215.9}));
  EXPECT_EQ(paper_size_mm("legal"), (Size{215.9, 355.6}));
  EXPECT_EQ(paper_size_mm("tabloid"), (Size{279.4, 431.8}));
  for (const char* text : {"A7", "B5", "A4landscape", "landscape", "A4 sideways", "", "a 4"}) {
    EXPECT_FALSE(paper_size_mm(text).has_value()) << text;
  }
  EXPECT_EQ(paper_names(), "A0, A1, A2, A3, A4, A5, A6, letter, legal, tabloid");
}

TEST(MatchChoice, AnyCaseGivesTheTablesSpelling) {
  const std::vector<std::string> rules = {"diw", "fdm", "plot"};
  EXPECT_EQ(match_choice("FDM", rules), "fdm");
  EXPECT_EQ(match_choice("Plot", rules), "plot");
  EXPECT_EQ(match_choice("fdm", rules), "fdm");
  EXPECT_FALSE(match_choice("fdmx", rules).has_value());
  EXPECT_FALSE(match_choice("", rules).has_value());
}

// The same rules through a parameter table: CLI text and job-file strings alike.
const ParamTable& table() {
  static const ParamTable t = {
      "demo",
      {
          {"nozzle", ParamType::Number, "mm", "d", 0.0, true, 10.0},
          {"rows", ParamType::Integer, "", "n", 1.0, false, 100.0},
          {"speed", ParamType::Number, "mm/min", "v", 0.0, true, 1e5},
          {"angles", ParamType::NumberList, "deg", "a", -360.0, false, 360.0},
          {"size", ParamType::Size2, "mm", "s", 0.0, true, 1000.0},
          {"fit", ParamType::Size2, "mm", "page", 0.0, true, std::nullopt, false, nullptr, "", {}, true},
          {"rules", ParamType::Text, "", "r", std::nullopt, false, std::nullopt, false, "diw", "", {"diw", "fdm", "plot"}},
          {"blur", ParamType::Integer, "px", "b", 0.0, false, 10.0},
      }};
  return t;
}

const ParamDef& def(const std::string& key) {
  for (const auto& d : table().defs) {
    if (d.key == key) return d;
  }
  throw std::logic_error(key);
}

std::string error_of(const std::string& key, const std::string& text) {
  try {
    parse_param_text(table(), def(key), text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(ParamUnits, CommandLineTextConvertsToTheTablesUnit) {
  EXPECT_EQ(parse_param_text(table(), def("nozzle"), "840um"), 0.84);
  EXPECT_EQ(parse_param_text(table(), def("speed"), "25mm/s"), 1500.0);
  EXPECT_EQ(parse_param_text(table(), def("angles"), "0,1.5708rad").size(), 2u);
  EXPECT_EQ(parse_param_text(table(), def("size"), "36mmx3.6cm"), nlohmann::json({36.0, 36.0}));
  EXPECT_EQ(parse_param_text(table(), def("fit"), "A4 landscape"), nlohmann::json({297.0, 210.0}));
  EXPECT_EQ(parse_param_text(table(), def("fit"), "190x270mm"), nlohmann::json({190.0, 270.0}));
  EXPECT_EQ(parse_param_text(table(), def("rows"), "4"), 4);
  EXPECT_EQ(parse_param_text(table(), def("blur"), "2px"), 2);
}

TEST(ParamUnits, WrongUnitsNameTheParameterAndTheExpectedUnits) {
  EXPECT_EQ(error_of("nozzle", "3mm/s"), "demo.nozzle = 3mm/s: expected a length (mm, cm, m, um, in)");
  EXPECT_EQ(error_of("rows", "4mm"), "demo.rows = 4mm: expected a plain number (no unit)");
  EXPECT_EQ(error_of("speed", "25mm"), "demo.speed = 25mm: expected a speed (mm/min, mm/s)");
  EXPECT_EQ(error_of("angles", "0,90mm"), "demo.angles = 0,90mm: expected an angle (deg, rad)");
  EXPECT_EQ(error_of("nozzle", "abc"), "demo.nozzle = abc: must be a number (mm)");
  EXPECT_EQ(error_of("rows", "2.5"), "demo.rows = 2.5: must be a whole number");
  EXPECT_EQ(error_of("size", "A4"), "demo.size = A4: must be a size like 36x36 (mm)");
  const std::string paper = error_of("fit", "B5");
  EXPECT_EQ(paper.rfind("demo.fit = B5: unknown paper (known: A0, A1, A2, A3, A4, A5, A6, letter, "
                        "legal, tabloid",
                        0),
            0u)
      << paper;
}

TEST(ParamUnits, JobFileStringsCarryUnitsAndNumbersStayAsTheyAre) {
  const auto v = resolve_params(table(), {{"nozzle", "0.84mm"},
                                          {"rows", 3},
                                          {"speed", "10 mm/s"},
                                          {"angles", nlohmann::json::array({"0deg", 90})},
                                          {"size", "36 x 36 mm"},
                                          {"fit", "letter"},
                                          {"rules", "FDM"}});
  EXPECT_EQ(v.at("nozzle"), 0.84);
  EXPECT_EQ(v.at("rows"), 3);
  EXPECT_EQ(v.at("speed"), 600.0);
  EXPECT_EQ(v.at("angles"), nlohmann::json({0.0, 90.0}));
  EXPECT_EQ(v.at("size"), nlohmann::json({36.0, 36.0}));
  EXPECT_EQ(v.at("fit"), nlohmann::json({215.9, 279.4}));
  EXPECT_EQ(v.at("rules"), "fdm") << "choices are normalised to the table's spelling";
  EXPECT_EQ(resolve_params(table(), {{"nozzle", 0.84}}).at("nozzle"), 0.84);
  try {
    resolve_params(table(), {{"nozzle", "3mm/s"}, {"rules", "cnc"}});
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("demo.nozzle = 3mm/s: expected a length (mm, cm, m, um, in)"), std::string::npos) << m;
    EXPECT_NE(m.find("demo.rules = cnc: must be one of diw, fdm, plot"), std::string::npos) << m;
  }
  // A converted value is checked against the range in the table's unit.
  EXPECT_THROW(resolve_params(table(), {{"nozzle", "1.1cm"}}), InputError);
  EXPECT_EQ(resolve_params(table(), {{"nozzle", "1cm"}}).at("nozzle"), 10.0);
}

}  // namespace
}  // namespace strand::slicer
